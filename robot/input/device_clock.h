// The robot's time base for live sensors, and the mapping of each device's
// own stamps onto it.
//
// The robot's time is the host's monotonic clock shifted once, at start, to
// read as the wall clock (Unix epoch nanoseconds, what the backbone and the
// logs compare): it never jumps when NTP steps the wall clock.
//
// A device stamps its readings on its own clock (a camera driver's buffer
// time, an IMU's counter, a GNSS receiver's UTC). A reading arrives after it
// was measured, never before, so each arrival a on the robot's clock bounds
// the offset between the clocks from above: offset <= a - d for the reading's
// device stamp d; the smallest a - d seen is the tightest bound, and the
// estimate, with the shortest delay as its only error (the one-way minimum
// delay, Paxson, "On calibrating measurements of packet transit times",
// SIGMETRICS 1998). A device clock may run slow or fast of the host's, so
// the estimate is offset_k = min(a_k - d_k, offset_k-1 + max_drift (a_k -
// a_k-1)): it falls at once to a tighter bound and rises no faster than a
// crystal's drift (100 ppm, doubled), so it follows the drift while a
// reading delayed more than the others does not pull it.
#pragma once

#include <cstdint>
#include <optional>

namespace lineloc {

class RobotTimeBase {
 public:
  RobotTimeBase();
  // Now on the robot's time base (ns).
  int64_t now() const;
  // A steady-clock reading on the robot's time base.
  int64_t fromSteady(int64_t steady_ns) const { return steady_ns + offset_ns_; }
  int64_t toSteady(int64_t robot_ns) const { return robot_ns - offset_ns_; }

 private:
  int64_t offset_ns_;
};

class DeviceClock {
 public:
  explicit DeviceClock(double max_drift = 200e-6) : max_drift_(max_drift) {}

  // Learns from a reading stamped `device_ns` that arrived at `arrival_ns`
  // (robot time). Of readings that arrive together, the newest bounds the
  // offset tightest: observe it before mapping them.
  void observe(int64_t device_ns, int64_t arrival_ns);

  // Observes the reading, then maps its stamp onto the robot's time: device_ns
  // + offset, and after a later stamp of the device than the last, never at
  // or before the last one mapped (a tighter bound can lower the offset by
  // more than the readings' spacing).
  int64_t map(int64_t device_ns, int64_t arrival_ns);

 private:
  double max_drift_;
  bool known_ = false;
  int64_t offset_ns_ = 0;
  int64_t last_arrival_ns_ = 0;
  std::optional<int64_t> last_device_ns_;
  int64_t last_mapped_ns_ = 0;
};

}  // namespace lineloc
