#include <gtest/gtest.h>

#include <thread>

#include "common/parallel/thread_priority.h"

namespace lineloc {
namespace {

int threadNice() {
  return getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
}

TEST(ThreadPriority, LowersOnlyTheCallingThreadAndWhatItStarts) {
  const int caller_nice = threadNice();
  int lowered_nice = 0;
  int started_nice = 0;
  std::thread background([&] {
    ASSERT_TRUE(lowerThreadPriority(caller_nice + 7));
    lowered_nice = threadNice();
    std::thread started([&] { started_nice = threadNice(); });
    started.join();
  });
  background.join();
  EXPECT_EQ(lowered_nice, caller_nice + 7);
  EXPECT_EQ(started_nice, caller_nice + 7);
  EXPECT_EQ(threadNice(), caller_nice);
}

}  // namespace
}  // namespace lineloc
