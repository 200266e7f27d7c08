// Keeps a process's background work (the backbone's pose searches, its map
// preparation) from running beside its latency-bound work (answering a
// tracked frame). Foreground work holds a Scope while it runs; a thread that
// runs as background work of the gate (BackgroundOf) calls yieldToForeground
// between pieces of its work, and waits there while any Scope is open.
// parallelFor (parallel_for.h) does so before each index it hands out, on
// every thread it starts for a background caller, so the searches need no
// yield points of their own; a piece that is running when a frame arrives
// runs to its end.
//
// A lower priority is not enough: a tracked frame's parallel threads start
// and wake beside niced (even SCHED_IDLE) background threads, which slow it
// by half or more; the answers slowest to come are those beside a search.
//
// Foreground work that comes at a known time (a tracked robot's next frame)
// can be announced: from expectForegroundFrom's time on, background work waits
// as if a Scope were open, until one opens or max_yield_ns has passed. So no
// piece is still running when the frame arrives, and none runs while the robot
// extracts its lines when both share the machine.
//
// Background work never starves: after a wait of w, the gate's background runs
// at least w before any of its threads waits again (the threads parallelFor
// starts anew for each call among them), so it keeps half of its time however
// busy the foreground is (a backbone serving many robots), and no single wait
// exceeds max_yield_ns.
//
// Cancelling ends the background work for good, for a process that stops
// whatever work is under way: background work no longer waits, and a
// parallelFor it calls skips the indices it has not started and throws
// BackgroundWorkCancelled.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <limits>
#include <mutex>
#include <stdexcept>

#include "common/time/clock.h"

namespace lineloc {

class ForegroundGate {
 public:
  explicit ForegroundGate(int64_t max_yield_ns) : max_yield_ns_(max_yield_ns) {}
  ForegroundGate(const ForegroundGate&) = delete;
  ForegroundGate& operator=(const ForegroundGate&) = delete;

  // Foreground work is in progress while a Scope lives.
  class Scope {
   public:
    explicit Scope(ForegroundGate& gate) : gate_(gate) { gate_.enter(); }
    ~Scope() { gate_.leave(); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    ForegroundGate& gate_;
  };

  // Background work steps aside from `steady_ns` (steadyClockNs) on, as described above; replaces
  // the time announced before.
  void expectForegroundFrom(int64_t steady_ns);

  // Blocks while a Scope is open or announced foreground work is due, at most
  // max_yield_ns, unless the background has not yet run as long as it last
  // waited or has been cancelled.
  void yieldToForeground();

  // Cancels the background work (see above); it cannot be resumed.
  void cancelBackground();
  bool backgroundCancelled() const { return cancelled_; }

 private:
  void enter();
  void leave();
  bool foregroundAt(int64_t steady_ns) const;

  const int64_t max_yield_ns_;
  std::atomic<int> open_scopes_{0};
  std::atomic<int64_t> expected_from_ns_{std::numeric_limits<int64_t>::max()};
  // Steady-clock time before which background work does not wait again.
  std::atomic<int64_t> runs_until_ns_{0};
  std::atomic<bool> cancelled_{false};
  std::mutex mutex_;
  std::condition_variable closed_;
};

// What a parallelFor of cancelled background work throws.
class BackgroundWorkCancelled : public std::runtime_error {
 public:
  BackgroundWorkCancelled() : std::runtime_error("background work cancelled") {}
};

// The gate whose background work the calling thread runs (nullptr: none).
ForegroundGate* backgroundGate();

// Makes the calling thread background work of `gate` while it lives.
class BackgroundOf {
 public:
  explicit BackgroundOf(ForegroundGate* gate);
  ~BackgroundOf();
  BackgroundOf(const BackgroundOf&) = delete;
  BackgroundOf& operator=(const BackgroundOf&) = delete;

 private:
  ForegroundGate* previous_;
};

// ---------------------------------------------------------------------------

namespace detail {

inline thread_local ForegroundGate* t_background_gate = nullptr;

}  // namespace detail

inline void ForegroundGate::enter() {
  const std::lock_guard<std::mutex> lock(mutex_);
  ++open_scopes_;
}

inline void ForegroundGate::leave() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    --open_scopes_;
  }
  closed_.notify_all();
}

inline void ForegroundGate::expectForegroundFrom(int64_t steady_ns) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    expected_from_ns_ = steady_ns;
  }
  // Inside a Scope its leave() wakes the background; waking it here too would
  // only switch it in beside the foreground to wait again.
  if (open_scopes_ == 0) {
    closed_.notify_all();
  }
}

inline void ForegroundGate::cancelBackground() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    cancelled_ = true;
  }
  closed_.notify_all();
}

inline bool ForegroundGate::foregroundAt(int64_t steady_ns) const {
  if (cancelled_) {
    return false;
  }
  const int64_t expected_ns = expected_from_ns_;
  return open_scopes_ > 0 || (steady_ns >= expected_ns && steady_ns - expected_ns < max_yield_ns_);
}

inline void ForegroundGate::yieldToForeground() {
  const int64_t start_ns = steadyClockNs();
  if (!foregroundAt(start_ns) || start_ns < runs_until_ns_) {
    return;
  }
  {
    std::unique_lock<std::mutex> lock(mutex_);
    closed_.wait_for(lock, std::chrono::nanoseconds(max_yield_ns_),
                     [this] { return !foregroundAt(steadyClockNs()); });
  }
  const int64_t end_ns = steadyClockNs();
  runs_until_ns_ = end_ns + (end_ns - start_ns);
}

inline ForegroundGate* backgroundGate() {
  return detail::t_background_gate;
}

inline BackgroundOf::BackgroundOf(ForegroundGate* gate) : previous_(detail::t_background_gate) {
  detail::t_background_gate = gate;
}

inline BackgroundOf::~BackgroundOf() {
  detail::t_background_gate = previous_;
}

}  // namespace lineloc
