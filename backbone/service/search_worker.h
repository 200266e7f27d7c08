// Runs the searches for the camera of robots whose prediction is poor (a DGPS
// + compass start takes a search of about a tenth of a second,
// pose_acquisition.h) on a thread of their own, so that every LineSet is
// answered while they run. One search per robot at a time: a robot's next
// search is accepted once its last one has finished; and at most max_queued
// searches wait in all, so that the searches of many robots (or of many
// made-up robot ids) neither grow without bound nor keep a robot's search
// waiting for long. The backbone prepares its maps on one too
// (prepared_maps.h), under a single key. Given a gate, the worker is its
// background work (foreground_gate.h): a job starts, and each piece of its
// parallelFor runs, only once the frames being answered are.
//
// Stopping (stop(), or destruction) drops the searches still queued and waits
// only for the one running, so that a service stops promptly whatever is
// queued; cancelling the gate's background work first ends that one too at
// its next piece (a search that throws BackgroundWorkCancelled ends there).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <limits>
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
  explicit SearchWorker(ForegroundGate* gate = nullptr,
                        size_t max_queued = std::numeric_limits<size_t>::max());
  // Stops (see stop()).
  ~SearchWorker();
  SearchWorker(const SearchWorker&) = delete;
  SearchWorker& operator=(const SearchWorker&) = delete;

  enum class Submitted {
    kQueued,
    // Nothing queued: the robot's previous search is still queued or running.
    kRobotBusy,
    // Nothing queued: max_queued searches wait already, or the worker stopped.
    kQueueFull,
  };
  Submitted submit(const std::string& robot_id, Search search);

  // Drops the searches queued, refuses new ones and waits for the one
  // running to finish.
  void stop();

  // Blocks until every accepted search has finished or been dropped.
  void waitUntilIdle();

 private:
  struct Job {
    std::string robot_id;
    Search search;
  };

  void work();

  ForegroundGate* const gate_;
  const size_t max_queued_;
  std::mutex mutex_;
  std::condition_variable job_ready_;
  std::condition_variable idle_;
  std::deque<Job> jobs_;
  std::set<std::string> busy_robots_;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace lineloc
