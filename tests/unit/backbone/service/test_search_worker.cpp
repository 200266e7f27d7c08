// The search worker: one search per robot at a time, every accepted search
// published, queued searches finished before it is destroyed.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <mutex>
#include <vector>

#include "backbone/service/search_worker.h"

namespace lineloc {
namespace {

PoseFixData fixFor(const std::string& robot_id, uint32_t sequence) {
  PoseFixData fix;
  fix.robot_id = robot_id;
  fix.sequence_number = sequence;
  return fix;
}

TEST(SearchWorker, RefusesASecondSearchForARobotWhileItsFirstRuns) {
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::mutex mutex;
  std::vector<PoseFixData> published;
  {
    SearchWorker worker([&](const PoseFixData& fix) {
      const std::lock_guard<std::mutex> lock(mutex);
      published.push_back(fix);
    });
    ASSERT_TRUE(worker.submit("rover1", [released] {
      released.wait();
      return fixFor("rover1", 1);
    }));
    EXPECT_FALSE(worker.submit("rover1", [] { return fixFor("rover1", 2); }));
    EXPECT_TRUE(worker.submit("rover2", [] { return fixFor("rover2", 7); }));
    release.set_value();
  }
  ASSERT_EQ(published.size(), 2u);
  EXPECT_EQ(published[0].sequence_number, 1u);
  EXPECT_EQ(published[1].robot_id, "rover2");
}

TEST(SearchWorker, TakesTheRobotsNextSearchOnceTheLastIsPublished) {
  std::atomic<int> published{0};
  SearchWorker worker([&](const PoseFixData&) { ++published; });
  ASSERT_TRUE(worker.submit("rover1", [] { return fixFor("rover1", 1); }));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!worker.submit("rover1", [] { return fixFor("rover1", 2); })) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline);
    std::this_thread::yield();
  }
  EXPECT_GE(published.load(), 1);
}

}  // namespace
}  // namespace lineloc
