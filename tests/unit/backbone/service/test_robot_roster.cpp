// The robots a backbone serves: at most max_robots, served robots never
// pushed out by new ones, silent ones forgotten to make room.
#include <gtest/gtest.h>

#include <string>

#include "backbone/service/robot_roster.h"

namespace lineloc {
namespace {

constexpr int64_t kSecondNs = 1'000'000'000;
using Heard = RobotRoster::Heard;

TEST(RobotRoster, ServesAtMostMaxRobotsAndNeverPushesOutAServedOne) {
  RobotRoster roster(3, 30 * kSecondNs);
  EXPECT_EQ(roster.hear("rover1", 0), Heard::kNew);
  EXPECT_EQ(roster.hear("rover1", 1), Heard::kServed);
  int refused = 0;
  for (int robot = 0; robot < 6000; ++robot) {
    refused += roster.hear("made-up-" + std::to_string(robot), 2 + robot) == Heard::kRefused;
  }
  EXPECT_EQ(refused, 6000 - 2);
  EXPECT_EQ(roster.size(), 3u);
  EXPECT_EQ(roster.hear("rover1", kSecondNs), Heard::kServed);
  EXPECT_TRUE(roster.serves("rover1"));
  EXPECT_TRUE(roster.serves("made-up-1"));
  EXPECT_FALSE(roster.serves("made-up-2"));
}

TEST(RobotRoster, ForgetsTheSilentRobotsToMakeRoom) {
  RobotRoster roster(2, 30 * kSecondNs);
  ASSERT_EQ(roster.hear("rover1", 0), Heard::kNew);
  ASSERT_EQ(roster.hear("made-up", 0), Heard::kNew);
  EXPECT_EQ(roster.hear("rover2", kSecondNs), Heard::kRefused);
  EXPECT_EQ(roster.hear("rover1", 20 * kSecondNs), Heard::kServed);
  EXPECT_TRUE(roster.forgetSilent(30 * kSecondNs).empty()) << "silent for exactly 30 s";
  const auto forgotten = roster.forgetSilent(31 * kSecondNs);
  ASSERT_EQ(forgotten.size(), 1u);
  EXPECT_EQ(forgotten[0].robot_id, "made-up");
  EXPECT_EQ(forgotten[0].silent_ns, 31 * kSecondNs);
  EXPECT_EQ(roster.hear("rover2", 31 * kSecondNs), Heard::kNew);
  EXPECT_EQ(roster.size(), 2u);
}

// A robot another backbone serves from now on is forgotten at once, making
// room; one not served is not.
TEST(RobotRoster, ForgetsARobotLeftToAnotherBackbone) {
  RobotRoster roster(1, 30 * kSecondNs);
  ASSERT_EQ(roster.hear("rover1", 0), Heard::kNew);
  EXPECT_FALSE(roster.forget("rover2"));
  EXPECT_TRUE(roster.forget("rover1"));
  EXPECT_FALSE(roster.serves("rover1"));
  EXPECT_EQ(roster.hear("rover2", kSecondNs), Heard::kNew);
}

TEST(RobotRoster, RefusesAnEmptyRoster) {
  EXPECT_THROW(RobotRoster(0, kSecondNs), std::invalid_argument);
  EXPECT_THROW(RobotRoster(1, 0), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
