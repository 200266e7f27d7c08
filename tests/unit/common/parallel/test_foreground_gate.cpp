// ForegroundGate: background work, on every thread parallelFor starts for it,
// waits while a foreground scope is open and once announced foreground work
// is due, not before; foreground work never waits; and a scope that stays
// open holds background work back for at most the gate's max_yield_ns.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <limits>
#include <thread>
#include <vector>

#include "common/parallel/foreground_gate.h"
#include "common/parallel/parallel_for.h"

namespace lineloc {
namespace {

constexpr int64_t kNoTimeout_ns = 60'000'000'000;
constexpr int kPieces = 8;

// Runs parallelFor's kPieces on two threads as background work of `gate` and
// returns, per piece, whether `foreground_done` was set when it started.
std::vector<char> backgroundPieces(ForegroundGate& gate, const std::atomic<bool>& foreground_done) {
  std::vector<char> saw_done(kPieces);
  std::thread background([&] {
    const BackgroundOf as_background(&gate);
    parallelFor(kPieces, 2, [&](int i) { saw_done[static_cast<size_t>(i)] = foreground_done; });
  });
  background.join();
  return saw_done;
}

// Whether background work of `gate` runs all its pieces within 30 s while the
// caller holds on to whatever foreground state it set up.
bool backgroundFinishesMeanwhile(ForegroundGate& gate) {
  const std::atomic<bool> foreground_done{false};
  std::future<std::vector<char>> pieces =
      std::async(std::launch::async, [&] { return backgroundPieces(gate, foreground_done); });
  return pieces.wait_for(std::chrono::seconds(30)) == std::future_status::ready &&
         pieces.get().size() == static_cast<size_t>(kPieces);
}

TEST(ForegroundGate, BackgroundWorkWaitsUntilTheForegroundScopeCloses) {
  ForegroundGate gate(kNoTimeout_ns);
  std::atomic<bool> foreground_done{false};
  std::future<std::vector<char>> pieces;
  {
    const ForegroundGate::Scope foreground(gate);
    pieces =
        std::async(std::launch::async, [&] { return backgroundPieces(gate, foreground_done); });
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    foreground_done = true;
  }
  for (const char saw_done : pieces.get()) {
    EXPECT_TRUE(saw_done);
  }
}

TEST(ForegroundGate, BackgroundWorkWaitsOnceAnnouncedForegroundWorkIsDue) {
  ForegroundGate gate(kNoTimeout_ns);
  std::atomic<bool> foreground_done{false};
  gate.expectForegroundFrom(steadyClockNs());
  std::future<std::vector<char>> pieces =
      std::async(std::launch::async, [&] { return backgroundPieces(gate, foreground_done); });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  foreground_done = true;
  gate.expectForegroundFrom(std::numeric_limits<int64_t>::max());
  for (const char saw_done : pieces.get()) {
    EXPECT_TRUE(saw_done);
  }
}

TEST(ForegroundGate, BackgroundWorkRunsBeforeAnnouncedForegroundWorkIsDue) {
  ForegroundGate gate(kNoTimeout_ns);
  gate.expectForegroundFrom(steadyClockNs() + kNoTimeout_ns);
  EXPECT_TRUE(backgroundFinishesMeanwhile(gate));
}

TEST(ForegroundGate, ForegroundWorkDoesNotWaitForAnOpenScope) {
  ForegroundGate gate(kNoTimeout_ns);
  const ForegroundGate::Scope foreground(gate);
  EXPECT_EQ(backgroundGate(), nullptr);
  std::atomic<int> pieces{0};
  parallelFor(kPieces, 2, [&](int) { ++pieces; });
  EXPECT_EQ(pieces.load(), kPieces);
}

TEST(ForegroundGate, AScopeLeftOpenHoldsBackgroundWorkOnlyForTheMaximumYield) {
  ForegroundGate gate(20'000'000);
  const ForegroundGate::Scope foreground(gate);
  EXPECT_TRUE(backgroundFinishesMeanwhile(gate));
}

TEST(ForegroundGate, BackgroundOfRestoresTheThreadsPreviousGate) {
  ForegroundGate outer(kNoTimeout_ns);
  ForegroundGate inner(kNoTimeout_ns);
  {
    const BackgroundOf first(&outer);
    {
      const BackgroundOf second(&inner);
      EXPECT_EQ(backgroundGate(), &inner);
    }
    EXPECT_EQ(backgroundGate(), &outer);
  }
  EXPECT_EQ(backgroundGate(), nullptr);
}

}  // namespace
}  // namespace lineloc
