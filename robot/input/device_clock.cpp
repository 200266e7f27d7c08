#include "robot/input/device_clock.h"

#include <algorithm>
#include <cmath>

#include "common/time/clock.h"

namespace lineloc {

RobotTimeBase::RobotTimeBase() : offset_ns_(wallClockNs() - steadyClockNs()) {}

int64_t RobotTimeBase::now() const {
  return fromSteady(steadyClockNs());
}

void DeviceClock::observe(int64_t device_ns, int64_t arrival_ns) {
  const int64_t bound_ns = arrival_ns - device_ns;
  const int64_t risen_ns =
      offset_ns_ + std::llround(max_drift_ * static_cast<double>(arrival_ns - last_arrival_ns_));
  offset_ns_ = known_ ? std::min(bound_ns, risen_ns) : bound_ns;
  known_ = true;
  last_arrival_ns_ = std::max(last_arrival_ns_, arrival_ns);
}

int64_t DeviceClock::map(int64_t device_ns, int64_t arrival_ns) {
  observe(device_ns, arrival_ns);
  int64_t mapped_ns = device_ns + offset_ns_;
  if (last_device_ns_ && device_ns > *last_device_ns_) {
    mapped_ns = std::max(mapped_ns, last_mapped_ns_ + 1);
  }
  last_device_ns_ = device_ns;
  last_mapped_ns_ = mapped_ns;
  return mapped_ns;
}

}  // namespace lineloc
