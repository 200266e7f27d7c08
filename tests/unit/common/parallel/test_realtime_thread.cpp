#include <gtest/gtest.h>

#include <thread>

#include "common/parallel/realtime_thread.h"

namespace lineloc {
namespace {

int threadPolicy() {
  int policy = -1;
  sched_param parameters{};
  pthread_getschedparam(pthread_self(), &policy, &parameters);
  return policy;
}

TEST(RealtimeThread, PriorityZeroLeavesTheThreadTimeShared) {
  std::thread thread([] {
    EXPECT_FALSE(runThreadRealtimeLogged(0, "test thread"));
    EXPECT_EQ(threadPolicy(), SCHED_OTHER);
  });
  thread.join();
}

// Granted or refused (the privilege depends on the machine), the answer is
// what the thread now runs under.
TEST(RealtimeThread, SaysWhetherTheThreadNowRunsUnderSchedFifo) {
  std::thread thread([] {
    const bool realtime = runThreadRealtimeLogged(3, "test thread");
    EXPECT_EQ(threadPolicy() == SCHED_FIFO, realtime);
  });
  thread.join();
}

}  // namespace
}  // namespace lineloc
