#include "backbone/service/fair_frame_queue.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace lineloc {
namespace {

constexpr double kNegligibleServiceNs = 1e3;

}  // namespace

FairFrameQueue::FairFrameQueue(int workers, double service_half_life_s)
    : workers_(workers), half_life_ns_(service_half_life_s * 1e9) {
  if (workers < 1) {
    throw std::invalid_argument("FairFrameQueue: at least one worker must answer the frames");
  }
  if (!(service_half_life_s > 0.0)) {
    throw std::invalid_argument("FairFrameQueue: the service half-life must be positive");
  }
}

FairFrameQueue::Pushed FairFrameQueue::push(LineSetData line_set, int64_t taken_ns) {
  notePeriod(line_set);
  Pushed pushed;
  const std::string& robot_id = line_set.robot_id;
  if (const auto waiting = waiting_.find(robot_id); waiting != waiting_.end()) {
    pushed.superseded = std::move(waiting->second.line_set);
    waiting_.erase(waiting);
  }
  const Service& service = service_[robot_id];
  const double wait_ns = expectedWaitNs(robot_id, taken_ns);
  if (wait_ns > 0.0 && service.period_ns > 0 &&
      wait_ns + service.frame_ns > static_cast<double>(service.period_ns)) {
    pushed.late = std::move(line_set);
    return pushed;
  }
  std::string key = robot_id;
  waiting_.emplace(std::move(key), Taken{std::move(line_set), taken_ns});
  return pushed;
}

void FairFrameQueue::notePeriod(const LineSetData& line_set) {
  Service& service = service_[line_set.robot_id];
  if (service.last_stamp_ns != 0) {
    service.period_ns = std::max<int64_t>(line_set.stamp_ns - service.last_stamp_ns, 0);
  }
  service.last_stamp_ns = line_set.stamp_ns;
}

double FairFrameQueue::serviceAt(const std::string& robot_id, int64_t now_ns) const {
  const auto service = service_.find(robot_id);
  if (service == service_.end()) {
    return 0.0;
  }
  const double elapsed_ns = static_cast<double>(now_ns - service->second.updated_ns);
  return service->second.service_ns * std::exp2(-std::max(elapsed_ns, 0.0) / half_life_ns_);
}

double FairFrameQueue::frameTimeOf(const std::string& robot_id) const {
  const auto service = service_.find(robot_id);
  return service == service_.end() ? 0.0 : service->second.frame_ns;
}

double FairFrameQueue::expectedWaitNs(const std::string& robot_id, int64_t now_ns) const {
  const double own_service_ns = serviceAt(robot_id, now_ns);
  double ahead_ns = 0.0;
  int ahead = 0;
  for (const auto& [waiting_robot, taken] : waiting_) {
    if (serviceAt(waiting_robot, now_ns) <= own_service_ns) {
      ahead_ns += frameTimeOf(waiting_robot);
      ++ahead;
    }
  }
  double own_remaining_ns = 0.0;
  for (const auto& [robot_in_hand, since_ns] : in_hand_) {
    const double remaining_ns =
        std::max(frameTimeOf(robot_in_hand) - static_cast<double>(now_ns - since_ns), 0.0);
    ahead_ns += remaining_ns;
    if (robot_in_hand == robot_id) {
      own_remaining_ns = remaining_ns;
    }
  }
  const int free_workers = workers_ - static_cast<int>(in_hand_.size());
  if (!in_hand_.contains(robot_id) && ahead < free_workers) {
    return 0.0;
  }
  return std::max(ahead_ns / workers_, own_remaining_ns);
}

std::optional<FairFrameQueue::Taken> FairFrameQueue::pop(int64_t now_ns) {
  auto next = waiting_.end();
  double next_service_ns = 0.0;
  for (auto waiting = waiting_.begin(); waiting != waiting_.end(); ++waiting) {
    if (in_hand_.contains(waiting->first)) {
      continue;
    }
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
  in_hand_[next->first] = now_ns;
  Taken taken = std::move(next->second);
  waiting_.erase(next);
  return taken;
}

void FairFrameQueue::done(const std::string& robot_id, int64_t service_ns, int64_t now_ns) {
  in_hand_.erase(robot_id);
  Service& service = service_[robot_id];
  const double handled_ns = static_cast<double>(std::max<int64_t>(service_ns, 0));
  service.service_ns = serviceAt(robot_id, now_ns) + handled_ns;
  service.updated_ns = now_ns;
  service.frame_ns = service.frame_ns == 0.0
                         ? handled_ns
                         : service.frame_ns + kFrameTimeWeight * (handled_ns - service.frame_ns);
  forgetNegligibleService(now_ns);
}

void FairFrameQueue::forgetNegligibleService(int64_t now_ns) {
  if (static_cast<double>(now_ns - forgotten_ns_) < half_life_ns_) {
    return;
  }
  forgotten_ns_ = now_ns;
  for (auto service = service_.begin(); service != service_.end();) {
    if (!waiting_.contains(service->first) && !in_hand_.contains(service->first) &&
        serviceAt(service->first, now_ns) < kNegligibleServiceNs) {
      service = service_.erase(service);
    } else {
      ++service;
    }
  }
}

}  // namespace lineloc
