// Runs a task every period on a thread of its own, from construction until
// destruction: work that must go on beside a latency-critical loop without
// ever holding it up: a file written on a serving thread can take a hundred
// milliseconds while other processes write theirs, and every message arriving
// meanwhile waits (the backbone's stats file).
//
// The task runs a period after construction, then a period after each run
// ended; destruction wakes the thread at once and waits only for a run under
// way. The task must not throw: nothing would be left to catch it.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

namespace lineloc {

class PeriodicTask {
 public:
  PeriodicTask(std::chrono::nanoseconds period, std::function<void()> task)
      : period_(period), task_(std::move(task)), thread_([this] { run(); }) {}

  ~PeriodicTask() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    stop_requested_.notify_all();
    thread_.join();
  }

  PeriodicTask(const PeriodicTask&) = delete;
  PeriodicTask& operator=(const PeriodicTask&) = delete;

 private:
  void run() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_requested_.wait_for(lock, period_, [this] { return stopping_; })) {
      lock.unlock();
      task_();
      lock.lock();
    }
  }

  const std::chrono::nanoseconds period_;
  const std::function<void()> task_;
  std::mutex mutex_;
  std::condition_variable stop_requested_;
  bool stopping_ = false;
  // Last: it starts running once the members above exist.
  std::thread thread_;
};

}  // namespace lineloc
