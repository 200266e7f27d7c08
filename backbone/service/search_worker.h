// Searches for the camera of robots whose prediction is poor (a DGPS + compass
// start takes a search of a few hundred milliseconds, pose_acquisition.h) on a
// thread of their own, so that the LineSets of robots being tracked are
// answered meanwhile. One search per robot at a time: a robot's LineSets that
// arrive while its search runs are answered at once, without a pose, and its
// next LineSet after the search starts the next one. Each search publishes the
// PoseFix of the LineSet it was given when it is done.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include "common/messages/messages.h"

namespace lineloc {

class SearchWorker {
 public:
  using Search = std::function<PoseFixData()>;
  using Publish = std::function<void(const PoseFixData&)>;

  explicit SearchWorker(Publish publish);
  // Finishes the search that is running and every one queued.
  ~SearchWorker();
  SearchWorker(const SearchWorker&) = delete;
  SearchWorker& operator=(const SearchWorker&) = delete;

  // Queues `search` for `robot_id`; false (nothing queued) when that robot's
  // previous search is still queued or running.
  bool submit(const std::string& robot_id, Search search);

 private:
  struct Job {
    std::string robot_id;
    Search search;
  };

  void work();

  Publish publish_;
  std::mutex mutex_;
  std::condition_variable job_ready_;
  std::deque<Job> jobs_;
  std::set<std::string> busy_robots_;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace lineloc
