// The backbone's pool answering LineSets: robots answered at once, each
// robot's frames in order and one at a time, a frame that would be late
// answered busy at once, and the frames waiting dropped on stopping.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "backbone/service/frame_workers.h"
#include "common/time/clock.h"

namespace lineloc {
namespace {

constexpr int64_t k30HzNs = 33'000'000;

// Frame `k` of a robot sending one every `period_ns`.
LineSetData frame(const std::string& robot_id, uint32_t k, int64_t period_ns = k30HzNs) {
  LineSetData line_set;
  line_set.robot_id = robot_id;
  line_set.sequence_number = k;
  line_set.stamp_ns = 1'000'000'000 + k * period_ns;
  return line_set;
}

// Answers that take `answer_for` each and record what happens: how many
// frames are answered at once, in all and per robot, the order of each
// robot's answers, and the busy ones.
class Recorder {
 public:
  explicit Recorder(std::chrono::milliseconds answer_for) : answer_for_(answer_for) {}

  FrameWorkers::Answers answers() {
    return {.answer = [this](const LineSetData& line_set, int64_t) { return answer(line_set); },
            .busy =
                [this](const LineSetData& line_set, int64_t, FrameRefusal why) {
                  const std::lock_guard<std::mutex> lock(mutex_);
                  busy_.push_back(
                      {line_set.robot_id + "#" + std::to_string(line_set.sequence_number), why});
                  PoseFixData fix;
                  fix.robot_id = line_set.robot_id;
                  fix.sequence_number = line_set.sequence_number;
                  fix.status = lineloc_msg_FIX_BUSY;
                  return fix;
                },
            .publish =
                [this](const PoseFixData& fix) {
                  const std::lock_guard<std::mutex> lock(mutex_);
                  published_.push_back(fix);
                }};
  }

  // Blocks until `count` frames have started being answered.
  void waitForStarted(int count) {
    std::unique_lock<std::mutex> lock(mutex_);
    started_changed_.wait(lock, [&] { return started_ >= count; });
  }

  std::mutex mutex_;
  int max_at_once_ = 0;
  std::map<std::string, int> max_at_once_per_robot_;
  std::map<std::string, std::vector<uint32_t>> answered_;
  std::vector<std::pair<std::string, FrameRefusal>> busy_;
  std::vector<PoseFixData> published_;

 private:
  PoseFixData answer(const LineSetData& line_set) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      ++started_;
      max_at_once_ = std::max(max_at_once_, ++at_once_);
      int& robot = at_once_per_robot_[line_set.robot_id];
      max_at_once_per_robot_[line_set.robot_id] =
          std::max(max_at_once_per_robot_[line_set.robot_id], ++robot);
    }
    started_changed_.notify_all();
    std::this_thread::sleep_for(answer_for_);
    const std::lock_guard<std::mutex> lock(mutex_);
    --at_once_;
    --at_once_per_robot_[line_set.robot_id];
    answered_[line_set.robot_id].push_back(line_set.sequence_number);
    PoseFixData fix;
    fix.robot_id = line_set.robot_id;
    fix.sequence_number = line_set.sequence_number;
    fix.status = lineloc_msg_FIX_OK;
    return fix;
  }

  const std::chrono::milliseconds answer_for_;
  std::condition_variable started_changed_;
  int started_ = 0;
  int at_once_ = 0;
  std::map<std::string, int> at_once_per_robot_;
};

TEST(FrameWorkers, AnswersTheFramesOfDifferentRobotsAtOnce) {
  Recorder recorder(std::chrono::milliseconds(50));
  FrameWorkers workers(3, recorder.answers());
  EXPECT_EQ(workers.threads(), 3);
  for (const char* robot : {"a", "b", "c"}) {
    workers.take(frame(robot, 0), steadyClockNs());
  }
  workers.waitUntilIdle();
  EXPECT_EQ(recorder.max_at_once_, 3);
  EXPECT_EQ(recorder.published_.size(), 3u);
  EXPECT_TRUE(recorder.busy_.empty());
}

// A robot's next frame, taken while its last is answered, waits for it
// though threads are free, and is answered after it (within its 100 ms
// period).
TEST(FrameWorkers, AnswersEachRobotsFramesInOrderOneAtATime) {
  Recorder recorder(std::chrono::milliseconds(20));
  FrameWorkers workers(4, recorder.answers());
  for (uint32_t k = 0; k < 5; ++k) {
    workers.take(frame("rover", k, 100'000'000), steadyClockNs());
    recorder.waitForStarted(static_cast<int>(k) + 1);
  }
  workers.waitUntilIdle();
  EXPECT_EQ(recorder.max_at_once_per_robot_["rover"], 1);
  EXPECT_EQ(recorder.answered_["rover"], (std::vector<uint32_t>{0, 1, 2, 3, 4}));
}

// One thread, frames taking 30 ms, two robots at 30 Hz: taken while the
// other robot's frame is answered, a frame would be answered about 60 ms
// after it came, past its robot's next: it is answered busy at once, before
// the frame in hand is done.
TEST(FrameWorkers, AnswersBusyAtOnceAFrameThatWouldBeAnsweredAfterItsRobotsNext) {
  Recorder recorder(std::chrono::milliseconds(30));
  FrameWorkers workers(1, recorder.answers());
  int started = 0;
  for (uint32_t k = 0; k < 2; ++k) {
    for (const char* robot : {"a", "b"}) {
      workers.take(frame(robot, k), steadyClockNs());
      recorder.waitForStarted(++started);
      workers.waitUntilIdle();
    }
  }
  workers.take(frame("a", 2), steadyClockNs());
  recorder.waitForStarted(++started);
  workers.take(frame("b", 2), steadyClockNs());
  {
    const std::lock_guard<std::mutex> lock(recorder.mutex_);
    ASSERT_EQ(recorder.busy_.size(), 1u);
    EXPECT_EQ(recorder.busy_[0].first, "b#2");
    EXPECT_EQ(recorder.busy_[0].second, FrameRefusal::kLate);
    EXPECT_EQ(recorder.answered_["a"].size(), 2u) << "a's frame 2 is still in hand";
    EXPECT_EQ(recorder.published_.back().status, lineloc_msg_FIX_BUSY);
  }
  workers.waitUntilIdle();
  EXPECT_EQ(recorder.answered_["a"].size(), 3u);
  EXPECT_EQ(recorder.answered_["b"].size(), 2u);
}

TEST(FrameWorkers, ASupersededFrameIsAnsweredBusy) {
  Recorder recorder(std::chrono::milliseconds(30));
  FrameWorkers workers(1, recorder.answers());
  workers.take(frame("a", 0), steadyClockNs());
  recorder.waitForStarted(1);
  workers.take(frame("b", 0), steadyClockNs());
  workers.take(frame("b", 1), steadyClockNs());
  workers.waitUntilIdle();
  ASSERT_EQ(recorder.busy_.size(), 1u);
  EXPECT_EQ(recorder.busy_[0].first, "b#0");
  EXPECT_EQ(recorder.busy_[0].second, FrameRefusal::kSuperseded);
  EXPECT_EQ(recorder.answered_["b"], std::vector<uint32_t>{1});
}

TEST(FrameWorkers, StoppingDropsTheFramesWaitingAndEndsTheOneInHand) {
  Recorder recorder(std::chrono::milliseconds(30));
  {
    FrameWorkers workers(1, recorder.answers());
    workers.take(frame("a", 0), steadyClockNs());
    recorder.waitForStarted(1);
    workers.take(frame("b", 0), steadyClockNs());
  }
  EXPECT_EQ(recorder.answered_["a"].size(), 1u);
  EXPECT_TRUE(recorder.answered_["b"].empty());
  EXPECT_EQ(recorder.published_.size(), 1u);
}

TEST(FrameWorkers, RefusesNoThreadsOrMissingAnswers) {
  Recorder recorder(std::chrono::milliseconds(1));
  EXPECT_THROW(FrameWorkers(0, recorder.answers()), std::invalid_argument);
  FrameWorkers::Answers missing = recorder.answers();
  missing.busy = nullptr;
  EXPECT_THROW(FrameWorkers(1, missing), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
