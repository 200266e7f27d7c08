// The search worker: one search per robot at a time and at most max_queued
// waiting in all, every accepted search run, the queued ones dropped when it
// stops and the running one ended when its background work is cancelled, and
// none started while a frame is being answered.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "backbone/service/search_worker.h"
#include "common/parallel/parallel_for.h"

namespace lineloc {
namespace {

using Submitted = SearchWorker::Submitted;

TEST(SearchWorker, RefusesASecondSearchForARobotWhileItsFirstRuns) {
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::mutex mutex;
  std::vector<std::string> finished;
  const auto finish = [&](const std::string& search) {
    const std::lock_guard<std::mutex> lock(mutex);
    finished.push_back(search);
  };
  SearchWorker worker;
  ASSERT_EQ(worker.submit("rover1",
                          [&, released] {
                            released.wait();
                            finish("rover1 #1");
                          }),
            Submitted::kQueued);
  EXPECT_EQ(worker.submit("rover1", [&] { finish("rover1 #2"); }), Submitted::kRobotBusy);
  EXPECT_EQ(worker.submit("rover2", [&] { finish("rover2 #7"); }), Submitted::kQueued);
  release.set_value();
  worker.waitUntilIdle();
  EXPECT_EQ(finished, (std::vector<std::string>{"rover1 #1", "rover2 #7"}));
}

TEST(SearchWorker, TakesTheRobotsNextSearchOnceTheLastHasFinished) {
  std::atomic<int> finished{0};
  SearchWorker worker;
  ASSERT_EQ(worker.submit("rover1", [&] { ++finished; }), Submitted::kQueued);
  worker.waitUntilIdle();
  EXPECT_EQ(finished.load(), 1);
  ASSERT_EQ(worker.submit("rover1", [&] { ++finished; }), Submitted::kQueued);
  worker.waitUntilIdle();
  EXPECT_EQ(finished.load(), 2);
}

// Many robots' searches: at most max_queued wait beside the one running; the
// rest are refused at once, and a robot whose search was refused is taken
// once the queue has room again.
TEST(SearchWorker, QueuesAtMostMaxQueuedSearchesOfAllRobots) {
  std::promise<void> running;
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<int> finished{0};
  SearchWorker worker(nullptr, 3);
  ASSERT_EQ(worker.submit("running",
                          [&, released] {
                            running.set_value();
                            released.wait();
                            ++finished;
                          }),
            Submitted::kQueued);
  running.get_future().wait();
  int queued = 0;
  int refused = 0;
  for (int robot = 0; robot < 300; ++robot) {
    const Submitted submitted =
        worker.submit("made-up-" + std::to_string(robot), [&] { ++finished; });
    (submitted == Submitted::kQueued ? queued : refused) += 1;
    EXPECT_NE(submitted, Submitted::kRobotBusy);
  }
  EXPECT_EQ(queued, 3);
  EXPECT_EQ(queued + refused, 300);
  EXPECT_EQ(worker.submit("running", [] {}), Submitted::kRobotBusy);
  release.set_value();
  worker.waitUntilIdle();
  EXPECT_EQ(finished.load(), 1 + queued);
  EXPECT_EQ(worker.submit("made-up-299", [&] { ++finished; }), Submitted::kQueued);
  worker.waitUntilIdle();
  EXPECT_EQ(finished.load(), 2 + queued);
}

// Stopping with many searches queued drops them and waits only for the one
// running: were any queued search run, it would never return and the test
// would time out.
TEST(SearchWorker, StopsPromptlyWhateverIsQueued) {
  std::promise<void> running;
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::promise<void> never;
  std::shared_future<void> never_set = never.get_future().share();
  std::atomic<int> started{0};
  SearchWorker worker;
  ASSERT_EQ(worker.submit("rover1",
                          [&, released] {
                            ++started;
                            running.set_value();
                            released.wait();
                          }),
            Submitted::kQueued);
  running.get_future().wait();
  for (int robot = 0; robot < 1000; ++robot) {
    ASSERT_EQ(worker.submit("made-up-" + std::to_string(robot),
                            [&, never_set] {
                              ++started;
                              never_set.wait();
                            }),
              Submitted::kQueued);
  }
  std::thread stopper([&] { worker.stop(); });
  // Once the worker refuses every search it has dropped the queued ones.
  for (int probe = 0;
       worker.submit("probe-" + std::to_string(probe), [] {}) != Submitted::kQueueFull; ++probe) {
    std::this_thread::yield();
  }
  release.set_value();
  stopper.join();
  EXPECT_EQ(started.load(), 1);
  worker.waitUntilIdle();
}

// A search running when its gate's background work is cancelled ends at its
// next piece: were it left to run, its billion pieces would not end before
// the test's timeout.
TEST(SearchWorker, StopsARunningSearchOnceItsBackgroundWorkIsCancelled) {
  ForegroundGate gate(1'000'000);
  std::promise<void> running;
  std::atomic<int> pieces{0};
  SearchWorker worker(&gate);
  ASSERT_EQ(worker.submit("rover1",
                          [&] {
                            parallelFor(1'000'000'000, 1, [&](int piece) {
                              if (piece == 0) {
                                running.set_value();
                              }
                              ++pieces;
                              std::this_thread::sleep_for(std::chrono::milliseconds(1));
                            });
                          }),
            Submitted::kQueued);
  running.get_future().wait();
  gate.cancelBackground();
  worker.stop();
  EXPECT_LT(pieces.load(), 1'000'000'000);
}

TEST(SearchWorker, StartsASearchOnlyOnceTheFrameBeingAnsweredIs) {
  ForegroundGate gate(60'000'000'000);
  std::atomic<bool> frame_answered{false};
  std::atomic<bool> started_after_frame{false};
  SearchWorker worker(&gate);
  {
    const ForegroundGate::Scope frame(gate);
    ASSERT_EQ(worker.submit("rover1", [&] { started_after_frame = frame_answered.load(); }),
              Submitted::kQueued);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    frame_answered = true;
  }
  worker.waitUntilIdle();
  EXPECT_TRUE(started_after_frame);
}

}  // namespace
}  // namespace lineloc
