#include <gtest/gtest.h>

#include "common/messages/robot_partition.h"

namespace lineloc {
namespace {

TEST(RobotPartition, IsTheRobotsIdAfterTheCommonPrefix) {
  EXPECT_EQ(robotPartition("r7"), "robot.r7");
}

TEST(RobotPartition, AWriterSpeaksForTheRobotOfItsOnlyPartition) {
  EXPECT_TRUE(speaksFor({"robot.r7"}, "r7"));
  EXPECT_FALSE(speaksFor({"robot.r8"}, "r7"));
  EXPECT_FALSE(speaksFor({"robot.r7x"}, "r7"));
  EXPECT_FALSE(speaksFor({}, "r7")) << "the default partition speaks for no robot";
  EXPECT_FALSE(speaksFor({"robot.r7", "robot.r8"}, "r7")) << "a writer in two robots' partitions";
  EXPECT_FALSE(speaksFor({"robot.*"}, "r7")) << "a pattern is not the robot's partition";
}

}  // namespace
}  // namespace lineloc
