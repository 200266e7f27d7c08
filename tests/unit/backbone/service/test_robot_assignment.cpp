// Rendezvous assignment of robots to backbones: the same answer from any
// order of the same backbones, an even share each, and only the robots of a
// backbone that leaves move.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "backbone/service/robot_assignment.h"

namespace lineloc {
namespace {

std::vector<std::string> robots(int count) {
  std::vector<std::string> ids;
  for (int i = 0; i < count; ++i) {
    ids.push_back("robot-" + std::to_string(i));
  }
  return ids;
}

TEST(RobotAssignment, EveryOrderOfTheSameBackbonesGivesTheSameAnswer) {
  const std::vector<std::string> backbones = {"east", "west", "north"};
  std::vector<std::string> shuffled = {"north", "east", "west"};
  for (const std::string& robot : robots(200)) {
    EXPECT_EQ(servingBackbone(robot, backbones), servingBackbone(robot, shuffled));
  }
  EXPECT_EQ(servingBackbone("robot-1", {}), "");
  EXPECT_EQ(servingBackbone("robot-1", {"only"}), "only");
}

// 4,000 robots over 4 backbones: binomial, 1,000 each with a standard
// deviation of sqrt(4000 * 1/4 * 3/4) = 27; five of those either way.
TEST(RobotAssignment, EachBackboneServesAnEvenShare) {
  const std::vector<std::string> backbones = {"bb-1", "bb-2", "bb-3", "bb-4"};
  std::map<std::string, int> share;
  for (const std::string& robot : robots(4000)) {
    ++share[servingBackbone(robot, backbones)];
  }
  ASSERT_EQ(share.size(), 4u);
  for (const auto& [backbone, served] : share) {
    EXPECT_NEAR(served, 1000, 5 * 27) << backbone;
  }
}

TEST(RobotAssignment, OnlyTheRobotsOfABackboneThatLeavesMove) {
  const std::vector<std::string> all = {"bb-1", "bb-2", "bb-3"};
  const std::vector<std::string> without_bb2 = {"bb-1", "bb-3"};
  int moved = 0;
  for (const std::string& robot : robots(1000)) {
    const std::string before = servingBackbone(robot, all);
    const std::string after = servingBackbone(robot, without_bb2);
    if (before != "bb-2") {
      EXPECT_EQ(after, before) << robot;
    } else {
      ++moved;
    }
  }
  EXPECT_GT(moved, 250);
}

TEST(RobotAssignment, WeightsOfNamesDifferingInOneCharacterAreUnrelated) {
  EXPECT_NE(assignmentWeight("bb-1", "robot-1"), assignmentWeight("bb-1", "robot-2"));
  EXPECT_NE(assignmentWeight("ab", "c"), assignmentWeight("a", "bc"));
}

}  // namespace
}  // namespace lineloc
