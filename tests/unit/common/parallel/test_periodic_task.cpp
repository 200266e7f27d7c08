// PeriodicTask runs its task repeatedly on its own thread, never holds up
// the thread that owns it, and stops at destruction without waiting out a
// period.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <thread>

#include "common/parallel/periodic_task.h"

namespace lineloc {
namespace {

using namespace std::chrono_literals;

// Waits (up to a minute: a loaded machine is slow, not wrong) for `runs` to
// reach `at_least`.
bool eventually(const std::atomic<int>& runs, int at_least) {
  const auto give_up = std::chrono::steady_clock::now() + 60s;
  while (runs.load() < at_least) {
    if (std::chrono::steady_clock::now() > give_up) {
      return false;
    }
    std::this_thread::sleep_for(1ms);
  }
  return true;
}

TEST(PeriodicTask, RunsAgainEachPeriodAndNotAfterDestruction) {
  std::atomic<int> runs{0};
  {
    const PeriodicTask task(1ms, [&runs] { ++runs; });
    EXPECT_TRUE(eventually(runs, 3));
  }
  const int after_destruction = runs.load();
  std::this_thread::sleep_for(20ms);
  EXPECT_EQ(runs.load(), after_destruction);
}

TEST(PeriodicTask, ItsOwnerGoesOnWhileARunIsHeldUp) {
  std::promise<void> release;
  const std::shared_future<void> released = release.get_future().share();
  std::atomic<int> runs{0};
  const PeriodicTask task(1ms, [&] {
    ++runs;
    released.wait();
  });
  // Here while the first run is blocked: it runs on the task's own thread.
  EXPECT_TRUE(eventually(runs, 1));
  EXPECT_EQ(runs.load(), 1);
  release.set_value();
  EXPECT_TRUE(eventually(runs, 2));
}

TEST(PeriodicTask, DestructionDoesNotWaitOutThePeriod) {
  std::atomic<int> runs{0};
  {
    const PeriodicTask task(std::chrono::hours(24), [&runs] { ++runs; });
  }
  // Reached at all: the destructor woke the thread out of its day-long wait,
  // before the first run was due.
  EXPECT_EQ(runs.load(), 0);
}

}  // namespace
}  // namespace lineloc
