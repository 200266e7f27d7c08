// The calling thread under SCHED_FIFO (runThreadRealtime, thread_priority.h),
// with the outcome in the log: a service's latency-critical thread asks for
// it at start, and a refusal must say what the machine lacks rather than
// leave the operator to find the thread time-shared in a latency report.
#pragma once

#include <spdlog/spdlog.h>

#include <string_view>

#include "common/parallel/thread_priority.h"

namespace lineloc {

// Puts the calling thread, `thread` in the log, under SCHED_FIFO at
// `priority` (0: leaves it time-shared and logs nothing); the threads it
// starts from then on inherit it. A refusal is logged as a warning naming
// the privilege it needs, and the thread runs on time-shared. Returns
// whether the thread now runs under SCHED_FIFO.
inline bool runThreadRealtimeLogged(int priority, std::string_view thread) {
  if (priority == 0) {
    return false;
  }
  if (!runThreadRealtime(priority)) {
    spdlog::warn(
        "realtime_priority {}: SCHED_FIFO refused (needs CAP_SYS_NICE or ulimit -r {}); the {} "
        "runs time-shared",
        priority, priority, thread);
    return false;
  }
  spdlog::info("the {} runs under SCHED_FIFO at priority {}", thread, priority);
  return true;
}

}  // namespace lineloc
