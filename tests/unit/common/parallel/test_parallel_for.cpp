// parallelFor: every index exactly once whatever the thread count, work
// really spread over threads, and a thrown exception brought back to the caller.
#include <gtest/gtest.h>
#include <sched.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "common/parallel/parallel_for.h"

namespace lineloc {
namespace {

TEST(ParallelFor, CallsEveryIndexExactlyOnce) {
  for (const int threads : {0, 1, 2, 3, 16}) {
    for (const int count : {0, 1, 2, 7, 1000}) {
      std::vector<std::atomic<int>> calls(static_cast<size_t>(count));
      parallelFor(count, threads, [&](int i) { ++calls[static_cast<size_t>(i)]; });
      for (int i = 0; i < count; ++i) {
        EXPECT_EQ(calls[static_cast<size_t>(i)], 1)
            << "index " << i << ", " << threads << " threads";
      }
    }
  }
}

// On a thread of its own, whose CPU affinity the test may change.
TEST(HardwareThreads, CountsTheCoresTheThreadMayRunOn) {
  std::thread([] {
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    ASSERT_EQ(sched_getaffinity(0, sizeof(allowed), &allowed), 0);
    EXPECT_EQ(hardwareThreads(), CPU_COUNT(&allowed));
    int first = 0;
    while (!CPU_ISSET(first, &allowed)) {
      ++first;
    }
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(first, &one);
    ASSERT_EQ(sched_setaffinity(0, sizeof(one), &one), 0);
    EXPECT_EQ(hardwareThreads(), 1);
  }).join();
}

TEST(ParallelFor, RunsOnAsManyThreadsAsAsked) {
  // Each call waits until three threads are inside: only possible when three run at once.
  std::atomic<int> inside{0};
  std::mutex mutex;
  std::set<std::thread::id> seen;
  parallelFor(3, 3, [&](int) {
    ++inside;
    while (inside < 3) {
      std::this_thread::yield();
    }
    const std::lock_guard<std::mutex> lock(mutex);
    seen.insert(std::this_thread::get_id());
  });
  EXPECT_EQ(seen.size(), 3u);
}

// Background work cancelled while its parallelFor runs: the indices not yet
// started are skipped (two threads: one may be inside its call already).
TEST(ParallelFor, SkipsTheIndicesLeftOnceItsBackgroundWorkIsCancelled) {
  ForegroundGate gate(1'000'000);
  const BackgroundOf background(&gate);
  std::atomic<int> calls{0};
  EXPECT_THROW(parallelFor(1000, 2,
                           [&](int) {
                             if (++calls == 10) {
                               gate.cancelBackground();
                             }
                           }),
               BackgroundWorkCancelled);
  EXPECT_GE(calls.load(), 10);
  EXPECT_LE(calls.load(), 11);
}

TEST(ParallelFor, RethrowsTheFirstExceptionOnTheCaller) {
  std::atomic<int> calls{0};
  EXPECT_THROW(parallelFor(100, 2,
                           [&](int i) {
                             ++calls;
                             if (i == 0) {
                               throw std::runtime_error("piece 0 failed");
                             }
                             std::this_thread::sleep_for(std::chrono::milliseconds(1));
                           }),
               std::runtime_error);
  // The other thread stops taking pieces once piece 0 has thrown.
  EXPECT_LT(calls.load(), 100);
}

}  // namespace
}  // namespace lineloc
