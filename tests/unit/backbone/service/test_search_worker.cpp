// The search worker: one search per robot at a time, every accepted search
// run, queued searches finished before it is destroyed, and none started
// while a frame is being answered.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "backbone/service/search_worker.h"

namespace lineloc {
namespace {

TEST(SearchWorker, RefusesASecondSearchForARobotWhileItsFirstRuns) {
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::mutex mutex;
  std::vector<std::string> finished;
  const auto finish = [&](const std::string& search) {
    const std::lock_guard<std::mutex> lock(mutex);
    finished.push_back(search);
  };
  {
    SearchWorker worker;
    ASSERT_TRUE(worker.submit("rover1", [&, released] {
      released.wait();
      finish("rover1 #1");
    }));
    EXPECT_FALSE(worker.submit("rover1", [&] { finish("rover1 #2"); }));
    EXPECT_TRUE(worker.submit("rover2", [&] { finish("rover2 #7"); }));
    release.set_value();
  }
  EXPECT_EQ(finished, (std::vector<std::string>{"rover1 #1", "rover2 #7"}));
}

TEST(SearchWorker, TakesTheRobotsNextSearchOnceTheLastHasFinished) {
  std::atomic<int> finished{0};
  SearchWorker worker;
  ASSERT_TRUE(worker.submit("rover1", [&] { ++finished; }));
  worker.waitUntilIdle();
  EXPECT_EQ(finished.load(), 1);
  ASSERT_TRUE(worker.submit("rover1", [&] { ++finished; }));
  worker.waitUntilIdle();
  EXPECT_EQ(finished.load(), 2);
}

TEST(SearchWorker, StartsASearchOnlyOnceTheFrameBeingAnsweredIs) {
  ForegroundGate gate(60'000'000'000);
  std::atomic<bool> frame_answered{false};
  std::atomic<bool> started_after_frame{false};
  SearchWorker worker(&gate);
  {
    const ForegroundGate::Scope frame(gate);
    ASSERT_TRUE(worker.submit("rover1", [&] { started_after_frame = frame_answered.load(); }));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    frame_answered = true;
  }
  worker.waitUntilIdle();
  EXPECT_TRUE(started_after_frame);
}

}  // namespace
}  // namespace lineloc
