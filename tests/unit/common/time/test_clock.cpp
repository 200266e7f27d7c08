// Clocks and the millisecond conversions of durations.
#include <gtest/gtest.h>

#include <cstdint>

#include "common/time/clock.h"

namespace lineloc {
namespace {

TEST(Clock, ConvertsDurationsBetweenNanosecondsAndMilliseconds) {
  EXPECT_DOUBLE_EQ(toMilliseconds(1'500'000), 1.5);
  EXPECT_DOUBLE_EQ(toMilliseconds(-250'000), -0.25);
  EXPECT_EQ(fromMilliseconds(2.5), 2'500'000);
  EXPECT_EQ(fromMilliseconds(0.0), 0);
  EXPECT_DOUBLE_EQ(toMilliseconds(static_cast<double>(fromMilliseconds(33.3))), 33.3);
}

TEST(Clock, SteadyClockNeverGoesBack) {
  const int64_t first_ns = steadyClockNs();
  const int64_t second_ns = steadyClockNs();
  EXPECT_GE(second_ns, first_ns);
  EXPECT_GT(wallClockNs(), 0);
}

}  // namespace
}  // namespace lineloc
