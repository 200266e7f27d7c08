// DeviceClock: a device's stamps land on the robot's time base at their
// shortest delay; a reading delayed more than the others does not move the
// mapping, and a device clock that runs slow is followed.
#include <gtest/gtest.h>

#include <random>

#include "common/time/clock.h"
#include "robot/input/device_clock.h"

namespace lineloc {
namespace {

constexpr int64_t kMs = 1'000'000;
constexpr int64_t kOffsetNs = 1'700'000'000'000'000'000;  // the device counts from 0

TEST(DeviceClock, StampsReadingsAtTheirShortestDelay) {
  DeviceClock clock;
  std::mt19937 random(3);
  std::uniform_int_distribution<int64_t> delay_ns(2 * kMs, 9 * kMs);
  for (int i = 0; i < 400; ++i) {
    const int64_t device_ns = i * 5 * kMs;  // a 200 Hz IMU
    // Every reading is 2-9 ms late, one in fifty by 80 ms more.
    const int64_t late_ns = delay_ns(random) + (i % 50 == 7 ? 80 * kMs : 0);
    const int64_t mapped_ns = clock.map(device_ns, kOffsetNs + device_ns + late_ns);
    if (i >= 20) {
      // Of 20 delays spread over 7 ms, the shortest is within 1 ms of 2 ms.
      EXPECT_NEAR(static_cast<double>(mapped_ns - (kOffsetNs + device_ns)), 2.0 * kMs, 1.0 * kMs)
          << i;
    }
  }
}

TEST(DeviceClock, FollowsADeviceClockRunningSlow) {
  DeviceClock clock;
  // The device's clock loses 50 ppm: one second of it is 1.00005 of the host's.
  for (int i = 0; i <= 100'000; ++i) {
    const int64_t robot_ns = kOffsetNs + i * 10 * kMs;  // 100 Hz for 1000 s
    const int64_t device_ns = static_cast<int64_t>(static_cast<double>(i * 10 * kMs) / 1.00005);
    const int64_t mapped_ns = clock.map(device_ns, robot_ns + kMs);
    // After 1000 s the clocks are 50 ms apart; the mapping stays at the 1 ms
    // delay within what one reading's drift adds.
    EXPECT_NEAR(static_cast<double>(mapped_ns - robot_ns), 1.0 * kMs, 0.01 * kMs) << i;
  }
}

// Ten readings that waited in a buffer and arrive at once keep their
// spacing once the newest, the tightest bound, is observed first; a later
// tighter bound never puts a reading before the one mapped last.
TEST(DeviceClock, ABurstKeepsItsSpacingAndStampsNeverGoBack) {
  DeviceClock clock;
  const int64_t arrival_ns = kOffsetNs + 50 * kMs;
  clock.observe(45 * kMs, arrival_ns);
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(clock.map(i * 5 * kMs, arrival_ns), kOffsetNs + i * 5 * kMs + 5 * kMs);
  }
  // The next reading arrives with 3 ms less delay than the burst's newest.
  const int64_t next_ns = clock.map(46 * kMs, kOffsetNs + 48 * kMs);
  EXPECT_GT(next_ns, kOffsetNs + 50 * kMs);
  EXPECT_EQ(clock.map(60 * kMs, kOffsetNs + 62 * kMs), kOffsetNs + 62 * kMs);
}

TEST(RobotTimeBase, ReadsAsTheWallClockAndMapsTheSteadyOne) {
  const RobotTimeBase time_base;
  const int64_t now_ns = time_base.now();
  EXPECT_NEAR(static_cast<double>(now_ns), static_cast<double>(wallClockNs()), 1e9);
  EXPECT_EQ(time_base.fromSteady(time_base.toSteady(now_ns)), now_ns);
}

}  // namespace
}  // namespace lineloc
