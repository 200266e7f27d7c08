#include "backbone/service/frame_cadence.h"

#include <algorithm>

namespace lineloc {
namespace {

// Consecutive stamps further apart than this are no frame period.
constexpr int64_t kMaxFramePeriod_ns = 1'000'000'000;

}  // namespace

FrameCadence::FrameCadence(int64_t lead_ns, int64_t stale_after_ns)
    : lead_ns_(lead_ns), stale_after_ns_(stale_after_ns) {}

void FrameCadence::add(const std::string& robot_id, int64_t stamp_ns, int64_t arrival_ns,
                       bool tracked) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Robot& robot = robots_[robot_id];
  const int64_t period_ns = stamp_ns - robot.stamp_ns;
  robot.stamp_ns = stamp_ns;
  robot.quiet_from_ns = tracked && period_ns > 0 && period_ns <= kMaxFramePeriod_ns
                            ? arrival_ns + period_ns - lead_ns_
                            : kNever;
}

int64_t FrameCadence::quietFrom_ns(int64_t now_ns) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  int64_t earliest_ns = kNever;
  for (const auto& [robot_id, robot] : robots_) {
    if (robot.quiet_from_ns >= now_ns - stale_after_ns_) {
      earliest_ns = std::min(earliest_ns, robot.quiet_from_ns);
    }
  }
  return earliest_ns;
}

void FrameCadence::forget(const std::function<bool(const std::string& robot_id)>& forgotten) {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::erase_if(robots_, [&](const auto& robot) { return forgotten(robot.first); });
}

}  // namespace lineloc
