#include "robot/vision/block_matching/kernel_timing.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

namespace lineloc {
namespace {

int64_t nowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

int64_t processCpuNs() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<int64_t>(now.tv_sec) * 1000000000 + now.tv_nsec;
}

uint64_t nowCycles() {
#if defined(__x86_64__) || defined(__i386__)
  return __rdtsc();
#else
  return 0;
#endif
}

// Median of a sorted, non-empty vector.
template <typename T>
double sortedMedian(const std::vector<T>& sorted) {
  const size_t n = sorted.size();
  return n % 2 == 1 ? static_cast<double>(sorted[n / 2])
                    : 0.5 * (static_cast<double>(sorted[n / 2 - 1]) + sorted[n / 2]);
}

// Linear-interpolated quantile q of a sorted, non-empty vector.
double sortedQuantile(const std::vector<int64_t>& sorted, double q) {
  const double position = q * static_cast<double>(sorted.size() - 1);
  const size_t below = static_cast<size_t>(position);
  const size_t above = std::min(below + 1, sorted.size() - 1);
  const double fraction = position - static_cast<double>(below);
  return (1.0 - fraction) * static_cast<double>(sorted[below]) +
         fraction * static_cast<double>(sorted[above]);
}

}  // namespace

bool hasCycleCounter() {
#if defined(__x86_64__) || defined(__i386__)
  return true;
#else
  return false;
#endif
}

RunTimer::RunTimer()
    : start_ns_(nowNs()), start_cycles_(nowCycles()), start_cpu_ns_(processCpuNs()) {}

RunSample RunTimer::elapsed() const {
  const uint64_t cycles = nowCycles();
  const int64_t cpu_ns = processCpuNs();
  return {nowNs() - start_ns_, cycles - start_cycles_, cpu_ns - start_cpu_ns_};
}

RunStatistics summarizeRuns(const std::vector<RunSample>& samples) {
  RunStatistics statistics;
  if (samples.empty()) {
    return statistics;
  }
  std::vector<int64_t> all_ns;
  for (const RunSample& sample : samples) {
    all_ns.push_back(sample.duration_ns);
  }
  std::sort(all_ns.begin(), all_ns.end());
  const double q1 = sortedQuantile(all_ns, 0.25);
  const double q3 = sortedQuantile(all_ns, 0.75);
  const double low = q1 - 1.5 * (q3 - q1);
  const double high = q3 + 1.5 * (q3 - q1);
  std::vector<int64_t> kept_ns;
  std::vector<uint64_t> kept_cycles;
  std::vector<int64_t> kept_cpu_ns;
  for (const RunSample& sample : samples) {
    if (sample.duration_ns >= low && sample.duration_ns <= high) {
      kept_ns.push_back(sample.duration_ns);
      kept_cycles.push_back(sample.duration_cycles);
      kept_cpu_ns.push_back(sample.cpu_ns);
    }
  }
  std::sort(kept_ns.begin(), kept_ns.end());
  std::sort(kept_cycles.begin(), kept_cycles.end());
  std::sort(kept_cpu_ns.begin(), kept_cpu_ns.end());
  statistics.runs = static_cast<int>(samples.size());
  statistics.kept = static_cast<int>(kept_ns.size());
  statistics.median_ns = sortedMedian(kept_ns);
  statistics.median_cycles = sortedMedian(kept_cycles);
  statistics.median_cpu_ns = sortedMedian(kept_cpu_ns);
  statistics.min_ns = static_cast<double>(all_ns.front());
  statistics.max_kept_ns = static_cast<double>(kept_ns.back());
  return statistics;
}

}  // namespace lineloc
