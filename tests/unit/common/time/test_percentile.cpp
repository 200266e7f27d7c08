// Nearest-rank percentiles.
#include <gtest/gtest.h>

#include <cstdint>

#include "common/time/percentile.h"

namespace lineloc {
namespace {

TEST(Percentile, IsTheNearestRankOfTheSortedSamples) {
  const std::vector<int64_t> latencies = {15, 20, 35, 40, 50};
  EXPECT_EQ(percentile(latencies, 0), 15);
  EXPECT_EQ(percentile(latencies, 30), 20);  // rank ceil(1.5) = 2
  EXPECT_EQ(percentile(latencies, 40), 20);  // rank 2
  EXPECT_EQ(percentile(latencies, 50), 35);  // rank ceil(2.5) = 3
  EXPECT_EQ(percentile(latencies, 100), 50);
  EXPECT_DOUBLE_EQ(percentile(std::vector<double>{3.0, 1.0, 2.0}, 50), 2.0);
}

TEST(Percentile, NoSamplesGiveZero) {
  EXPECT_EQ(percentile(std::vector<int64_t>{}, 99), 0);
}

}  // namespace
}  // namespace lineloc
