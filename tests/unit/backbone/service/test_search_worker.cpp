// The search worker: one search per robot at a time, every accepted search
// run, queued searches finished before it is destroyed.
#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <mutex>
#include <string>
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

}  // namespace
}  // namespace lineloc
