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

SearchWorker::SearchWorker(ForegroundGate* gate, size_t max_queued)
    : gate_(gate), max_queued_(max_queued), worker_([this] { work(); }) {}

SearchWorker::~SearchWorker() {
  stop();
}

void SearchWorker::stop() {
  std::deque<Job> dropped;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    dropped.swap(jobs_);
    for (const Job& job : dropped) {
      busy_robots_.erase(job.robot_id);
    }
    if (busy_robots_.empty()) {
      idle_.notify_all();
    }
  }
  job_ready_.notify_all();
  if (worker_.joinable()) {
    worker_.join();
  }
}

SearchWorker::Submitted SearchWorker::submit(const std::string& robot_id, Search search) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_ || jobs_.size() >= max_queued_) {
      return busy_robots_.contains(robot_id) ? Submitted::kRobotBusy : Submitted::kQueueFull;
    }
    if (!busy_robots_.insert(robot_id).second) {
      return Submitted::kRobotBusy;
    }
    jobs_.push_back({robot_id, std::move(search)});
  }
  job_ready_.notify_one();
  return Submitted::kQueued;
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
    if (stopping_) {
      return;
    }
    Job job = std::move(jobs_.front());
    jobs_.pop_front();
    lock.unlock();
    if (gate_) {
      gate_->yieldToForeground();
    }
    try {
      job.search();
    } catch (const BackgroundWorkCancelled&) {
      // The service stops: the search ends here.
    }
    lock.lock();
    busy_robots_.erase(job.robot_id);
    if (busy_robots_.empty()) {
      idle_.notify_all();
    }
  }
}

}  // namespace lineloc
