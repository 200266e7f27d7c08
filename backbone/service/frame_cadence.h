// When the backbone's next tracked frame is due: robots send a LineSet per
// camera frame, so a tracked robot's next one arrives about a frame period
// (the difference of its last two stamps) after its last one did. The
// earliest such time, less a lead, is when the backbone's searches step aside
// for it (foreground_gate.h): no search piece is then still running when the
// frame arrives, nor while the robot extracts its lines, when the two share a
// machine. Thread-safe.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <string>

namespace lineloc {

class FrameCadence {
 public:
  static constexpr int64_t kNever = std::numeric_limits<int64_t>::max();

  // `lead_ns` before a frame is due, background work steps aside; an
  // expectation more than `stale_after_ns` past is dropped (a robot that
  // stopped sending).
  FrameCadence(int64_t lead_ns, int64_t stale_after_ns);

  // Records `robot_id`'s frame stamped `stamp_ns`, which arrived at
  // `arrival_ns` (steady clock); a frame that was not tracked (searched, no
  // map) expects nothing of the robot's next one.
  void add(const std::string& robot_id, int64_t stamp_ns, int64_t arrival_ns, bool tracked);

  // The earliest time, at or after now_ns - stale_after_ns, from which
  // background work steps aside for a robot's next frame; kNever for none.
  int64_t quietFrom_ns(int64_t now_ns) const;

  // Drops the robots `forgotten` names (line_set_handler.h: silent robots).
  void forget(const std::function<bool(const std::string& robot_id)>& forgotten);

 private:
  struct Robot {
    int64_t stamp_ns = 0;
    int64_t quiet_from_ns = kNever;
  };

  const int64_t lead_ns_;
  const int64_t stale_after_ns_;
  mutable std::mutex mutex_;
  std::map<std::string, Robot> robots_;
};

}  // namespace lineloc
