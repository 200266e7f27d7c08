// Runs the searches for the camera of robots whose prediction is poor (a DGPS
// + compass start takes a search of about a tenth of a second,
// pose_acquisition.h) on a thread of their own, so that every LineSet is
// answered while they run. One search per robot at a time: a robot's next
// search is accepted once its last one has finished. The backbone prepares
// its maps on one too (prepared_maps.h), under a single key. Given a gate, the
// worker is its background work (foreground_gate.h): a job starts, and each
// piece of its parallelFor runs, only once the frames being answered are.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include "common/parallel/foreground_gate.h"

namespace lineloc {

class SearchWorker {
 public:
  using Search = std::function<void()>;

  // `gate` (may be null) must outlive the worker.
  explicit SearchWorker(ForegroundGate* gate = nullptr);
  // Finishes the search that is running and every one queued.
  ~SearchWorker();
  SearchWorker(const SearchWorker&) = delete;
  SearchWorker& operator=(const SearchWorker&) = delete;

  // Queues `search` for `robot_id`; false (nothing queued) when that robot's
  // previous search is still queued or running.
  bool submit(const std::string& robot_id, Search search);

  // Blocks until every accepted search has finished.
  void waitUntilIdle();

 private:
  struct Job {
    std::string robot_id;
    Search search;
  };

  void work();

  ForegroundGate* const gate_;
  std::mutex mutex_;
  std::condition_variable job_ready_;
  std::condition_variable idle_;
  std::deque<Job> jobs_;
  std::set<std::string> busy_robots_;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace lineloc
