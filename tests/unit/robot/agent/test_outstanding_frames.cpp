#include <gtest/gtest.h>

#include "robot/agent/outstanding_frames.h"

namespace lineloc {
namespace {

TEST(OutstandingFrames, AnAnswerIsTakenOnceForTheFrameItNames) {
  OutstandingFrames frames;
  frames.expect(0, {100, 1'000, 4'000, 90'000});
  frames.expect(1, {133, 1'033, 4'033, 90'033});
  EXPECT_FALSE(frames.answered(1));
  const auto frame = frames.take(1, 133);
  ASSERT_TRUE(frame.has_value());
  EXPECT_EQ(frame->exposure_steady_ns, 1'033);
  EXPECT_EQ(frame->sent_steady_ns, 4'033);
  EXPECT_EQ(frame->sent_wall_ns, 90'033);
  EXPECT_TRUE(frames.answered(1));
  EXPECT_FALSE(frames.take(1, 133).has_value()) << "answered twice";
  EXPECT_FALSE(frames.take(2, 166).has_value()) << "never sent";
  EXPECT_EQ(frames.size(), 1u);
}

TEST(OutstandingFrames, AnAnswerToTheRunBeforeARestartIsNotTaken) {
  OutstandingFrames frames;
  frames.expect(0, {5'000, 1'000, 4'000, 90'000});
  EXPECT_FALSE(frames.take(0, 2'000).has_value());
  EXPECT_FALSE(frames.answered(0));
  EXPECT_TRUE(frames.take(0, 5'000).has_value());
}

// Exposed at 1 ms and written at 4 ms on the steady clock, answered at 9 ms;
// the backbone worked 2 ms and wrote its answer at 8 ms. The wall clock read
// 90 ms when the LineSet was written and was then stepped 3 s ahead (as NTP
// does): the exposure -> fix latency and the front end, which the robot reads
// on its steady clock, stay 8 ms and 3 ms; only the legs that compare its wall
// clock with the backbone's carry the step.
TEST(FixLatency, TheRobotsOwnIntervalsIgnoreAWallClockStep) {
  const OutstandingFrames::Frame frame{100, 1'000'000, 4'000'000, 90'000'000};
  const int64_t step_ns = 3'000'000'000;
  const FixLatency unstepped = fixLatencyOf(frame, 9'000'000, 95'000'000, 94'000'000, 2'000'000);
  EXPECT_EQ(unstepped.total_ns, 8'000'000);
  EXPECT_EQ(unstepped.front_end_ns, 3'000'000);
  EXPECT_EQ(unstepped.to_backbone_ns, 2'000'000);
  EXPECT_EQ(unstepped.backbone_ns, 2'000'000);
  EXPECT_EQ(unstepped.back_ns, 1'000'000);
  const FixLatency stepped =
      fixLatencyOf(frame, 9'000'000, 95'000'000 + step_ns, 94'000'000 + step_ns, 2'000'000);
  EXPECT_EQ(stepped.total_ns, 8'000'000);
  EXPECT_EQ(stepped.front_end_ns, 3'000'000);
  EXPECT_EQ(stepped.to_backbone_ns, 2'000'000 + step_ns);
  EXPECT_EQ(stepped.back_ns, 1'000'000);
}

}  // namespace
}  // namespace lineloc
