// One job, run again and again on a thread of its own beside work of the
// caller's: runAlongside(here) starts the job on the helper, runs here() on
// the calling thread, and returns once both have ended. The robot's front end
// detects a frame's corners on it while it links and fits the frame's lines
// (feature_extractor.h): on a machine with a core to spare, the frame's
// features come back after the longer of the two instead of their sum.
//
// The thread starts at the first runAlongside, from the calling thread, so it
// runs under that thread's scheduling policy and priority (POSIX threads
// inherit them): a front end raised to SCHED_FIFO after its extractor was
// built gets a helper at the same priority. From then on each run is a mutex
// and two condition-variable wake-ups, with no allocation.
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

namespace lineloc {

class HelperThread {
 public:
  explicit HelperThread(std::function<void()> job) : job_(std::move(job)) {}
  HelperThread(const HelperThread&) = delete;
  HelperThread& operator=(const HelperThread&) = delete;

  ~HelperThread() {
    if (!thread_.joinable()) {
      return;
    }
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }

  // The job on the helper and here() on the caller, both to their end; then
  // rethrows what here() threw, else what the job threw. Not reentrant: one
  // caller at a time.
  template <typename Function>
  void runAlongside(const Function& here) {
    startJob();
    std::exception_ptr here_error;
    try {
      here();
    } catch (...) {
      here_error = std::current_exception();
    }
    const std::exception_ptr job_error = waitForJob();
    if (here_error) {
      std::rethrow_exception(here_error);
    }
    if (job_error) {
      std::rethrow_exception(job_error);
    }
  }

 private:
  void startJob() {
    if (!thread_.joinable()) {
      thread_ = std::thread([this] { serve(); });
    }
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      job_pending_ = true;
    }
    changed_.notify_all();
  }

  std::exception_ptr waitForJob() {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return !job_pending_; });
    return std::exchange(job_error_, nullptr);
  }

  void serve() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
      changed_.wait(lock, [this] { return job_pending_ || stopping_; });
      if (!job_pending_) {
        return;
      }
      lock.unlock();
      std::exception_ptr error;
      try {
        job_();
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      job_error_ = error;
      job_pending_ = false;
      changed_.notify_all();
    }
  }

  const std::function<void()> job_;
  std::mutex mutex_;
  std::condition_variable changed_;
  bool job_pending_ = false;  // started and not yet ended
  bool stopping_ = false;
  std::exception_ptr job_error_;
  std::thread thread_;
};

}  // namespace lineloc
