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

TEST(ThreadPriority, ARealtimePriorityIsZeroOrOneToNinetyNine) {
  for (const int priority : {0, 1, 99}) {
    EXPECT_NO_THROW(requireRealtimePriority(priority)) << priority;
  }
  for (const int priority : {-1, 100}) {
    EXPECT_THROW(requireRealtimePriority(priority), std::runtime_error) << priority;
  }
}

struct Scheduling {
  int policy = -1;
  int priority = -1;
};

Scheduling threadScheduling() {
  Scheduling scheduling;
  sched_param parameters{};
  pthread_getschedparam(pthread_self(), &scheduling.policy, &parameters);
  scheduling.priority = parameters.sched_priority;
  return scheduling;
}

// Without the privilege (an unprivileged user, a container without
// CAP_SYS_NICE) the refusal must leave the thread as it was.
TEST(ThreadPriority, RunsOnlyTheCallingThreadRealtimeOrLeavesItAsItWas) {
  const Scheduling caller = threadScheduling();
  bool granted = false;
  Scheduling realtime;
  std::thread latency_critical([&] {
    granted = runThreadRealtime(3);
    realtime = threadScheduling();
  });
  latency_critical.join();
  if (granted) {
    EXPECT_EQ(realtime.policy, SCHED_FIFO);
    EXPECT_EQ(realtime.priority, 3);
  } else {
    EXPECT_EQ(realtime.policy, caller.policy);
    EXPECT_EQ(realtime.priority, caller.priority);
  }
  EXPECT_EQ(threadScheduling().policy, caller.policy);
}

TEST(ThreadPriority, RefusesARealtimePriorityOutsideOneToNinetyNine) {
  std::thread latency_critical([] {
    EXPECT_FALSE(runThreadRealtime(0));
    EXPECT_FALSE(runThreadRealtime(100));
    EXPECT_EQ(threadScheduling().policy, SCHED_OTHER);
  });
  latency_critical.join();
}

}  // namespace
}  // namespace lineloc
