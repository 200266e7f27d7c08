// Runs the searches for the camera of robots whose prediction is poor (a DGPS
// + compass start takes a search of about a tenth of a second,
// pose_acquisition.h) on a thread of their own, so that every LineSet is
// answered while they run. One search per robot at a time: a robot's next
// search is accepted once its last one has finished. The backbone prepares
// its maps on one too (prepared_maps.h), under a single key.
//
// The worker runs below the threads a frame's answer waits on
// (thread_priority.h): at nice 10 for searches a robot waits on for its
// fixes, so that they still get a share of a busy machine; at SCHED_IDLE for
// searches nothing waits on (a proof of tracking, line_set_handler.h), so
// that they get no share of a core another thread wants. That does not make
// them free: on 50 simulated Delft drives, frames answered while a proof
// search ran took 14.8 ms from exposure to fix at the 99th percentile at
// nice 10 and 13.9 ms at SCHED_IDLE, against 10.7 and 10.3 ms for the others
// (about 530 frames of 21000 each time, so the 99th percentile is a handful).
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <thread>

namespace lineloc {

enum class SearchPriority { kBelowTracking, kIdle };

class SearchWorker {
 public:
  using Search = std::function<void()>;

  explicit SearchWorker(SearchPriority priority);
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

  void work(SearchPriority priority);

  std::mutex mutex_;
  std::condition_variable job_ready_;
  std::condition_variable idle_;
  std::deque<Job> jobs_;
  std::set<std::string> busy_robots_;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace lineloc
