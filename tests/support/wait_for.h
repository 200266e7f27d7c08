// Polling for a condition that another participant or process makes true.
#pragma once

#include <chrono>
#include <thread>

namespace lineloc::test {

// Calls `predicate` every 5 ms until it returns true (then true) or
// `timeout` has passed (then false).
template <typename Predicate>
bool waitFor(Predicate&& predicate, std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!predicate()) {
    if (std::chrono::steady_clock::now() > deadline) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

}  // namespace lineloc::test
