#include "robot/vision/block_matching/kernel_timing.h"

#include <gtest/gtest.h>

namespace lineloc {
namespace {

TEST(KernelTiming, OutliersOutsideTukeyFencesAreExcluded) {
  // Sorted: 100 100 101 102 103 104 104 106 1000; Q1 = 101, Q3 = 104, so the
  // fences are [96.5, 108.5]: the 1000 ns run is an outlier, 106 ns is not.
  std::vector<RunSample> samples;
  for (int64_t ns : {100, 101, 100, 102, 103, 104, 106, 104, 1000}) {
    samples.push_back({ns, static_cast<uint64_t>(3 * ns), 2 * ns});
  }
  const RunStatistics statistics = summarizeRuns(samples);
  EXPECT_EQ(statistics.runs, 9);
  EXPECT_EQ(statistics.kept, 8);
  EXPECT_DOUBLE_EQ(statistics.median_ns, 102.5);
  EXPECT_DOUBLE_EQ(statistics.median_cycles, 307.5);
  EXPECT_DOUBLE_EQ(statistics.median_cpu_ns, 205.0);
  EXPECT_DOUBLE_EQ(statistics.min_ns, 100.0);
  EXPECT_DOUBLE_EQ(statistics.max_kept_ns, 106.0);
}

TEST(KernelTiming, EmptyInputGivesZeros) {
  const RunStatistics statistics = summarizeRuns({});
  EXPECT_EQ(statistics.runs, 0);
  EXPECT_EQ(statistics.kept, 0);
  EXPECT_EQ(statistics.median_ns, 0.0);
}

TEST(KernelTiming, TimerCountsForwardOnEveryClock) {
  const RunTimer timer;
  volatile uint64_t sink = 0;
  for (int i = 0; i < 100000; ++i) {
    sink = sink + static_cast<uint64_t>(i);
  }
  const RunSample sample = timer.elapsed();
  EXPECT_GT(sample.duration_ns, 0);
  EXPECT_EQ(sample.duration_cycles > 0, hasCycleCounter());
  EXPECT_GE(sample.cpu_ns, 0);
}

}  // namespace
}  // namespace lineloc
