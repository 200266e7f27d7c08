// HelperThread runs its job on a thread of its own while the caller's work
// runs, returns only once both have ended, passes on what either threw, and
// serves run after run, a throwing one among them.
#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <stdexcept>
#include <thread>

#include "common/parallel/helper_thread.h"

namespace lineloc {
namespace {

TEST(HelperThread, RunsTheJobOnItsOwnThreadWhileTheCallerWorks) {
  std::promise<std::thread::id> job_thread;
  std::promise<void> job_started;
  std::shared_future<void> started = job_started.get_future().share();
  int runs = 0;
  HelperThread helper([&] {
    ++runs;
    job_thread.set_value(std::this_thread::get_id());
    job_started.set_value();
  });
  // The caller's work waits for the job to have started: were the job run
  // after it on the same thread, this would never return.
  helper.runAlongside([&] { started.wait(); });
  EXPECT_EQ(runs, 1);
  EXPECT_NE(job_thread.get_future().get(), std::this_thread::get_id());
}

TEST(HelperThread, ReturnsOnlyOnceTheJobHasEnded) {
  std::atomic<bool> job_ended{false};
  HelperThread helper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    job_ended = true;
  });
  for (int run = 0; run < 3; ++run) {
    job_ended = false;
    helper.runAlongside([] {});
    EXPECT_TRUE(job_ended.load()) << "run " << run;
  }
}

TEST(HelperThread, PassesOnWhatEitherSideThrewAndServesTheNextRun) {
  bool job_throws = true;
  int job_runs = 0;
  HelperThread helper([&] {
    ++job_runs;
    if (job_throws) {
      throw std::runtime_error("job failed");
    }
  });
  EXPECT_THROW(helper.runAlongside([] {}), std::runtime_error);
  // Both threw: the caller's own error is the one passed on.
  EXPECT_THROW(helper.runAlongside([] { throw std::logic_error("here failed"); }),
               std::logic_error);
  job_throws = false;
  EXPECT_NO_THROW(helper.runAlongside([] {}));
  EXPECT_THROW(helper.runAlongside([] { throw std::logic_error("here failed"); }),
               std::logic_error);
  EXPECT_EQ(job_runs, 4);
}

TEST(HelperThread, DestructionWithoutARunStartsNoThread) {
  int runs = 0;
  {
    const HelperThread helper([&runs] { ++runs; });
  }
  EXPECT_EQ(runs, 0);
}

}  // namespace
}  // namespace lineloc
