// Answers the LineSets a backbone takes on a pool of threads, one per core
// by default: the frames of many robots are answered at once, each robot's
// in order and one at a time, handed out fairly (fair_frame_queue.h). A
// frame superseded by its robot's next before a thread took it, or that
// would wait past its robot's next frame, is answered FIX_BUSY at once by
// the thread that takes it, and the robot dead-reckons on.
//
// Stopping (destruction) drops the frames still waiting, unanswered, and
// waits for those being answered.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "backbone/service/fair_frame_queue.h"
#include "common/messages/messages.h"

namespace lineloc {

class FrameWorkers {
 public:
  // What a frame's answer is made of; each is called from any of the
  // pool's threads and from take()'s caller.
  struct Answers {
    // The fix for a frame taken at `taken_ns` (steady clock).
    std::function<PoseFixData(const LineSetData& line_set, int64_t taken_ns)> answer;
    // FIX_BUSY for a frame not answered, and why.
    std::function<PoseFixData(const LineSetData& line_set, int64_t taken_ns, FrameRefusal why)>
        busy;
    // Sends an answer to its robot.
    std::function<void(const PoseFixData& fix)> publish;
  };

  // `threads` (at least one) answer frames; each first runs `start_thread`
  // when given (a real-time priority).
  FrameWorkers(int threads, Answers answers, std::function<void()> start_thread = {});
  ~FrameWorkers();
  FrameWorkers(const FrameWorkers&) = delete;
  FrameWorkers& operator=(const FrameWorkers&) = delete;

  // Queues an accepted LineSet taken at `taken_ns` (steady clock), answering
  // busy at once what it supersedes, or itself when it would be late.
  void take(LineSetData line_set, int64_t taken_ns);

  // Blocks until no frame waits and none is being answered.
  void waitUntilIdle();

  int threads() const { return static_cast<int>(threads_.size()); }

 private:
  void work();

  Answers answers_;
  std::mutex mutex_;
  std::condition_variable changed_;
  FairFrameQueue queue_;
  bool stopping_ = false;
  // Last, so that its threads stop before the members above go.
  std::vector<std::jthread> threads_;
};

}  // namespace lineloc
