// Background work below the threads a frame's answer waits on: the calling
// thread's Linux nice value (set per thread, and inherited by the threads it
// starts, parallelFor's among them) is raised to `nice`, so under load the
// scheduler gives it a share weighted 1024 / 1.25^nice of a nice-0 thread's.
// The backbone's pose searches take both cores for up to a second and the
// replay decodes a PNG per frame; at equal priority either holds back the
// tracked frames' answers, and at SCHED_IDLE the decoding starved during a
// search and held back the replay itself. Best effort: a refusal (lowering is
// always allowed, raising needs privilege) leaves the priority as it was.
#pragma once

#include <sys/resource.h>
#include <unistd.h>

namespace lineloc {

// Returns whether the calling thread now runs at `nice`.
inline bool lowerThreadPriority(int nice) {
  return setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), nice) == 0;
}

}  // namespace lineloc
