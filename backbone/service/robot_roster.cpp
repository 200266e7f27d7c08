#include "backbone/service/robot_roster.h"

#include <stdexcept>

namespace lineloc {

RobotRoster::RobotRoster(size_t max_robots, int64_t forget_after_ns)
    : max_robots_(max_robots), forget_after_ns_(forget_after_ns) {
  if (max_robots_ == 0 || forget_after_ns_ <= 0) {
    throw std::invalid_argument(
        "a robot roster needs room for a robot and a positive time to forget one after");
  }
}

RobotRoster::Heard RobotRoster::hear(const std::string& robot_id, int64_t now_ns) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (const auto found = last_heard_ns_.find(robot_id); found != last_heard_ns_.end()) {
    found->second = now_ns;
    return Heard::kServed;
  }
  if (last_heard_ns_.size() >= max_robots_) {
    return Heard::kRefused;
  }
  last_heard_ns_.emplace(robot_id, now_ns);
  return Heard::kNew;
}

bool RobotRoster::serves(const std::string& robot_id) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return last_heard_ns_.contains(robot_id);
}

std::vector<RobotRoster::Forgotten> RobotRoster::forgetSilent(int64_t now_ns) {
  std::vector<Forgotten> forgotten;
  const std::lock_guard<std::mutex> lock(mutex_);
  std::erase_if(last_heard_ns_, [&](const auto& robot) {
    const int64_t silent_ns = now_ns - robot.second;
    if (silent_ns <= forget_after_ns_) {
      return false;
    }
    forgotten.push_back({robot.first, silent_ns});
    return true;
  });
  return forgotten;
}

bool RobotRoster::forget(const std::string& robot_id) {
  const std::lock_guard<std::mutex> lock(mutex_);
  return last_heard_ns_.erase(robot_id) > 0;
}

size_t RobotRoster::size() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return last_heard_ns_.size();
}

}  // namespace lineloc
