#include <gtest/gtest.h>

#include "robot/agent/outstanding_frames.h"

namespace lineloc {
namespace {

TEST(OutstandingFrames, AnAnswerIsTakenOnceForTheFrameItNames) {
  OutstandingFrames frames;
  frames.expect(0, {100, 1'000, 4'000});
  frames.expect(1, {133, 1'033, 4'033});
  EXPECT_FALSE(frames.answered(1));
  const auto frame = frames.take(1, 133);
  ASSERT_TRUE(frame.has_value());
  EXPECT_EQ(frame->exposure_wall_ns, 1'033);
  EXPECT_EQ(frame->sent_wall_ns, 4'033);
  EXPECT_TRUE(frames.answered(1));
  EXPECT_FALSE(frames.take(1, 133).has_value()) << "answered twice";
  EXPECT_FALSE(frames.take(2, 166).has_value()) << "never sent";
  EXPECT_EQ(frames.size(), 1u);
}

TEST(OutstandingFrames, AnAnswerToTheRunBeforeARestartIsNotTaken) {
  OutstandingFrames frames;
  frames.expect(0, {5'000, 1'000, 4'000});
  EXPECT_FALSE(frames.take(0, 2'000).has_value());
  EXPECT_FALSE(frames.answered(0));
  EXPECT_TRUE(frames.take(0, 5'000).has_value());
}

}  // namespace
}  // namespace lineloc
