#include "backbone/service/search_worker.h"

#include <utility>

#include "common/parallel/thread_priority.h"

namespace lineloc {
namespace {

// Searches run below tracking, the DDS threads and, on a shared machine, the
// robot and its replay's decoding (thread_priority.h); SCHED_IDLE gains
// nothing over a nice value, the foreground gate already keeping the searches
// from running beside a tracked frame.
constexpr int kSearchNice = 10;

}  // namespace

SearchWorker::SearchWorker(ForegroundGate* gate) : gate_(gate), worker_([this] { work(); }) {}

SearchWorker::~SearchWorker() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  job_ready_.notify_all();
  worker_.join();
}

bool SearchWorker::submit(const std::string& robot_id, Search search) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!busy_robots_.insert(robot_id).second) {
      return false;
    }
    jobs_.push_back({robot_id, std::move(search)});
  }
  job_ready_.notify_one();
  return true;
}

void SearchWorker::waitUntilIdle() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return busy_robots_.empty(); });
}

void SearchWorker::work() {
  lowerThreadPriority(kSearchNice);
  const BackgroundOf background(gate_);
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    job_ready_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
    if (jobs_.empty()) {
      return;
    }
    Job job = std::move(jobs_.front());
    jobs_.pop_front();
    lock.unlock();
    if (gate_) {
      gate_->yieldToForeground();
    }
    job.search();
    lock.lock();
    busy_robots_.erase(job.robot_id);
    if (busy_robots_.empty()) {
      idle_.notify_all();
    }
  }
}

}  // namespace lineloc
