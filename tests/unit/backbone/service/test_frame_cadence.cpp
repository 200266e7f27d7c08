// FrameCadence: a tracked robot's next frame is due a frame period after its
// last arrived; the earliest robot's, less the lead, is announced, and
// nothing for robots searched for, just started, back after a gap, gone or
// forgotten.
#include <gtest/gtest.h>

#include "backbone/service/frame_cadence.h"

namespace lineloc {
namespace {

constexpr int64_t kMs = 1'000'000;
constexpr int64_t kPeriod_ns = 33 * kMs;
constexpr int64_t kLead_ns = 8 * kMs;
constexpr int64_t kStaleAfter_ns = 33 * kMs;
constexpr int64_t kStamp_ns = 1'776'159'000'000'000'000;
constexpr int64_t kArrival_ns = 5'000 * kMs;

TEST(FrameCadence, ExpectsATrackedRobotsNextFrameAFramePeriodAfterItsLastArrived) {
  FrameCadence cadence(kLead_ns, kStaleAfter_ns);
  cadence.add("rover1", kStamp_ns, kArrival_ns, true);
  EXPECT_EQ(cadence.quietFrom_ns(kArrival_ns), FrameCadence::kNever) << "one frame has no period";
  cadence.add("rover1", kStamp_ns + kPeriod_ns, kArrival_ns + 35 * kMs, true);
  EXPECT_EQ(cadence.quietFrom_ns(kArrival_ns + 40 * kMs),
            kArrival_ns + 35 * kMs + kPeriod_ns - kLead_ns);
}

TEST(FrameCadence, ExpectsNothingOfARobotWhoseLastFrameWasNotTracked) {
  FrameCadence cadence(kLead_ns, kStaleAfter_ns);
  cadence.add("rover1", kStamp_ns, kArrival_ns, true);
  cadence.add("rover1", kStamp_ns + kPeriod_ns, kArrival_ns + kPeriod_ns, false);
  EXPECT_EQ(cadence.quietFrom_ns(kArrival_ns + kPeriod_ns), FrameCadence::kNever);
}

TEST(FrameCadence, ExpectsNothingAfterAGapLongerThanAnyFramePeriod) {
  FrameCadence cadence(kLead_ns, kStaleAfter_ns);
  cadence.add("rover1", kStamp_ns, kArrival_ns, true);
  cadence.add("rover1", kStamp_ns + 2'000 * kMs, kArrival_ns + 2'000 * kMs, true);
  EXPECT_EQ(cadence.quietFrom_ns(kArrival_ns + 2'000 * kMs), FrameCadence::kNever);
}

TEST(FrameCadence, AnnouncesTheEarliestRobotsFrameUntilItIsStale) {
  FrameCadence cadence(kLead_ns, kStaleAfter_ns);
  cadence.add("rover1", kStamp_ns, kArrival_ns, true);
  cadence.add("rover2", kStamp_ns, kArrival_ns + 10 * kMs, true);
  cadence.add("rover1", kStamp_ns + kPeriod_ns, kArrival_ns + kPeriod_ns, true);
  cadence.add("rover2", kStamp_ns + 2 * kPeriod_ns, kArrival_ns + 15 * kMs, true);
  const int64_t rover1_quiet_ns = kArrival_ns + 2 * kPeriod_ns - kLead_ns;
  const int64_t rover2_quiet_ns = kArrival_ns + 15 * kMs + 2 * kPeriod_ns - kLead_ns;
  ASSERT_LT(rover1_quiet_ns, rover2_quiet_ns);
  EXPECT_EQ(cadence.quietFrom_ns(kArrival_ns + kPeriod_ns), rover1_quiet_ns);
  EXPECT_EQ(cadence.quietFrom_ns(rover1_quiet_ns + kStaleAfter_ns), rover1_quiet_ns);
  EXPECT_EQ(cadence.quietFrom_ns(rover1_quiet_ns + kStaleAfter_ns + 1), rover2_quiet_ns)
      << "rover1 stopped sending";
  EXPECT_EQ(cadence.quietFrom_ns(rover2_quiet_ns + kStaleAfter_ns + 1), FrameCadence::kNever);
}

TEST(FrameCadence, ExpectsNothingOfAForgottenRobot) {
  FrameCadence cadence(kLead_ns, kStaleAfter_ns);
  cadence.add("rover1", kStamp_ns, kArrival_ns, true);
  cadence.add("rover2", kStamp_ns, kArrival_ns + 10 * kMs, true);
  cadence.add("rover1", kStamp_ns + kPeriod_ns, kArrival_ns + kPeriod_ns, true);
  cadence.add("rover2", kStamp_ns + kPeriod_ns, kArrival_ns + 10 * kMs + kPeriod_ns, true);
  cadence.forget([](const std::string& robot_id) { return robot_id == "rover1"; });
  EXPECT_EQ(cadence.quietFrom_ns(kArrival_ns + kPeriod_ns),
            kArrival_ns + 10 * kMs + 2 * kPeriod_ns - kLead_ns);
  cadence.forget([](const std::string&) { return true; });
  EXPECT_EQ(cadence.quietFrom_ns(kArrival_ns + kPeriod_ns), FrameCadence::kNever);
}

}  // namespace
}  // namespace lineloc
