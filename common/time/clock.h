// Time stamps: int64 nanoseconds since the Unix epoch (CLOCK_REALTIME), the one
// clock that separate processes on a robot and a backbone can compare.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdint>
#include <ctime>

namespace lineloc {

inline int64_t wallClockNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// Monotonic nanoseconds for measuring durations inside one process.
inline int64_t steadyClockNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// A duration in milliseconds, for logs and reports: ms = 1e-6 ns.
constexpr double toMilliseconds(double duration_ns) {
  return 1e-6 * duration_ns;
}

// A duration given in milliseconds (options, logs) in nanoseconds, rounded to
// the nearest: 33.3 ms * 1e6 is 33299999.99... in binary.
inline int64_t fromMilliseconds(double duration_ms) {
  return std::llround(duration_ms * 1e6);
}

// CPU time this thread has used, for measuring work on a loaded machine.
inline int64_t threadCpuClockNs() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

}  // namespace lineloc
