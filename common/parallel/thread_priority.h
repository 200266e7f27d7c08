// Background work below the threads a frame's answer waits on: the calling
// thread's Linux nice value (set per thread, and inherited by the threads it
// starts, parallelFor's among them) is raised to `nice`, so under load the
// scheduler gives it a share weighted 1024 / 1.25^nice of a nice-0 thread's.
// The backbone's pose searches take both cores for up to a second and the
// replay decodes a PNG per frame; at equal priority either holds back the
// tracked frames' answers, and at SCHED_IDLE the decoding starved during a
// search and held back the replay itself. Best effort: a refusal (lowering is
// always allowed, raising needs privilege) leaves the priority as it was.
//
// Latency-critical work above them: runThreadRealtime puts the calling
// thread under SCHED_FIFO, which no time-shared thread preempts: on cores
// shared by the robot and the backbone, a backbone thread woken while the
// other core is busy is otherwise queued on the core extracting the robot's
// lines and preempts the extraction for milliseconds. A nice value does
// not prevent it: a thread waking from sleep is placed ahead of a running one
// however niced. It needs CAP_SYS_NICE or an RLIMIT_RTPRIO (ulimit -r) of at
// least the priority asked for.
#pragma once

#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <stdexcept>
#include <string>

namespace lineloc {

// Returns whether the calling thread now runs at `nice`.
inline bool lowerThreadPriority(int nice) {
  return setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), nice) == 0;
}

// Throws std::runtime_error naming the option `realtime_priority` unless
// `priority` is 0 (time-shared) or a SCHED_FIFO priority (1-99).
inline void requireRealtimePriority(int priority) {
  if (priority < 0 || priority > 99) {
    throw std::runtime_error("realtime_priority " + std::to_string(priority) +
                             " must be 0 (time-shared) or a SCHED_FIFO priority of 1-99");
  }
}

// Returns whether the calling thread now runs under SCHED_FIFO at `priority`
// (1-99); the threads it starts from then on inherit it.
inline bool runThreadRealtime(int priority) {
  sched_param parameters{};
  parameters.sched_priority = priority;
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &parameters) == 0;
}

}  // namespace lineloc
