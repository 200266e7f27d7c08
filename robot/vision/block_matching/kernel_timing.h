// Timing of repeated kernel runs as Persa & Jonker §4 measure their SIMD
// kernels: every run is timed both in nanoseconds (steady clock) and in
// time-stamp-counter cycles (RDTSC, constant rate on current x86 processors;
// not core cycles when the core clock differs from the TSC's), and runs
// outside Tukey's fences [Q1 - 1.5 IQR, Q3 + 1.5 IQR] of the nanoseconds
// (interrupts, page faults, migrations) are excluded before the medians.
#pragma once

#include <cstdint>
#include <vector>

namespace lineloc {

struct RunSample {
  int64_t duration_ns = 0;
  uint64_t duration_cycles = 0;  // 0 where there is no cycle counter
  // CPU time of the whole process (all threads) over the run: below
  // duration_ns when the run was preempted, above it when it used threads.
  int64_t cpu_ns = 0;
};

struct RunStatistics {
  int runs = 0;
  int kept = 0;  // runs inside the fences
  double median_ns = 0.0;
  double median_cycles = 0.0;
  double median_cpu_ns = 0.0;
  double min_ns = 0.0;
  double max_kept_ns = 0.0;
};

// True on x86, where RDTSC is read.
bool hasCycleCounter();

// Starts at construction; elapsed() reads both clocks.
class RunTimer {
 public:
  RunTimer();
  RunSample elapsed() const;

 private:
  int64_t start_ns_;
  uint64_t start_cycles_;
  int64_t start_cpu_ns_;
};

// Statistics of `samples`; all zero when it is empty.
RunStatistics summarizeRuns(const std::vector<RunSample>& samples);

}  // namespace lineloc
