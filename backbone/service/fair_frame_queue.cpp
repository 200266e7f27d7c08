#include "backbone/service/fair_frame_queue.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace lineloc {
namespace {

constexpr double kNegligibleServiceNs = 1e3;

}  // namespace

FairFrameQueue::FairFrameQueue(double service_half_life_s)
    : half_life_ns_(service_half_life_s * 1e9) {
  if (!(service_half_life_s > 0.0)) {
    throw std::invalid_argument("FairFrameQueue: the service half-life must be positive");
  }
}

std::optional<LineSetData> FairFrameQueue::push(LineSetData line_set, int64_t taken_ns) {
  std::string robot_id = line_set.robot_id;
  Taken taken{std::move(line_set), taken_ns};
  const auto [waiting, inserted] = waiting_.try_emplace(std::move(robot_id), std::move(taken));
  if (inserted) {
    return std::nullopt;
  }
  std::optional<LineSetData> superseded = std::move(waiting->second.line_set);
  waiting->second = std::move(taken);
  return superseded;
}

double FairFrameQueue::serviceAt(const std::string& robot_id, int64_t now_ns) const {
  const auto service = service_.find(robot_id);
  if (service == service_.end()) {
    return 0.0;
  }
  const double elapsed_ns = static_cast<double>(now_ns - service->second.updated_ns);
  return service->second.service_ns * std::exp2(-std::max(elapsed_ns, 0.0) / half_life_ns_);
}

std::optional<FairFrameQueue::Taken> FairFrameQueue::pop(int64_t now_ns) {
  auto next = waiting_.end();
  double next_service_ns = 0.0;
  for (auto waiting = waiting_.begin(); waiting != waiting_.end(); ++waiting) {
    const double service_ns = serviceAt(waiting->first, now_ns);
    if (next == waiting_.end() || service_ns < next_service_ns ||
        (service_ns == next_service_ns && waiting->second.taken_ns < next->second.taken_ns)) {
      next = waiting;
      next_service_ns = service_ns;
    }
  }
  if (next == waiting_.end()) {
    return std::nullopt;
  }
  Taken taken = std::move(next->second);
  waiting_.erase(next);
  return taken;
}

void FairFrameQueue::charge(const std::string& robot_id, int64_t service_ns, int64_t now_ns) {
  const double decayed_ns = serviceAt(robot_id, now_ns);
  service_[robot_id] = {decayed_ns + static_cast<double>(std::max<int64_t>(service_ns, 0)), now_ns};
  forgetNegligibleService(now_ns);
}

void FairFrameQueue::forgetNegligibleService(int64_t now_ns) {
  if (static_cast<double>(now_ns - forgotten_ns_) < half_life_ns_) {
    return;
  }
  forgotten_ns_ = now_ns;
  for (auto service = service_.begin(); service != service_.end();) {
    if (waiting_.count(service->first) == 0 &&
        serviceAt(service->first, now_ns) < kNegligibleServiceNs) {
      service = service_.erase(service);
    } else {
      ++service;
    }
  }
}

}  // namespace lineloc
