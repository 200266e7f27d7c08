// fn(i) for every i in [0, count) on a few threads, the caller's among them:
// each thread takes the next index from a shared counter, so uneven pieces of
// work even out. Meant for coarse pieces (a search cell, a hypothesis), not
// for inner loops: it starts its threads on every call. fn must be safe to
// call concurrently for different i. The first exception any call throws is
// rethrown on the caller once every thread has stopped; indices not yet
// started when it was thrown are skipped. Called from background work
// (foreground_gate.h), every thread yields to the foreground before each index,
// and the threads it starts are background work of the same gate; once that
// work is cancelled, the indices not yet started are skipped and it throws
// BackgroundWorkCancelled.
#pragma once

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "common/parallel/foreground_gate.h"

namespace lineloc {

// One thread per core the calling thread may run on (its CPU affinity, as
// taskset or a container's cpuset sets it), at least one.
inline int hardwareThreads() {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof(allowed), &allowed) == 0) {
    return std::max(1, CPU_COUNT(&allowed));
  }
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// threads <= 0: hardwareThreads().
template <typename Function>
void parallelFor(int count, int threads, const Function& fn) {
  const int used = std::min(count, threads > 0 ? threads : hardwareThreads());
  std::atomic<int> next{0};
  std::exception_ptr first_error;
  std::mutex error_mutex;
  ForegroundGate* const gate = backgroundGate();
  auto work = [&] {
    const BackgroundOf background(gate);
    for (int i = next++; i < count; i = next++) {
      try {
        if (gate) {
          gate->yieldToForeground();
          if (gate->backgroundCancelled()) {
            throw BackgroundWorkCancelled();
          }
        }
        fn(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!first_error) {
          first_error = std::current_exception();
        }
        next = count;
      }
    }
  };
  std::vector<std::thread> helpers;
  for (int t = 1; t < used; ++t) {
    helpers.emplace_back(work);
  }
  work();
  for (std::thread& helper : helpers) {
    helper.join();
  }
  if (first_error) {
    std::rethrow_exception(first_error);
  }
}

}  // namespace lineloc
