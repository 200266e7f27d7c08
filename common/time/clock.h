// Time stamps: int64 nanoseconds since the Unix epoch (CLOCK_REALTIME), the one
// clock that separate processes on a robot and a backbone can compare.
#pragma once

#include <chrono>
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

// CPU time this thread has used, for measuring work on a loaded machine.
inline int64_t threadCpuClockNs() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

}  // namespace lineloc
