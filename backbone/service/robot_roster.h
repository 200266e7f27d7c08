// The robots a backbone serves: each robot id it has heard from and when it
// last did, at most max_robots of them, so that made-up robot ids cannot grow
// its sessions without bound. A robot is served from its first frame heard
// while fewer than max_robots are; a new one is refused while that many are,
// and is served once a robot has been forgotten: one not heard from for
// forget_after_ns. A served robot is never pushed out by new ones.
// Thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace lineloc {

class RobotRoster {
 public:
  RobotRoster(size_t max_robots, int64_t forget_after_ns);

  enum class Heard { kServed, kNew, kRefused };
  // Records that `robot_id` was heard from at `now_ns` (steady clock):
  // kServed for a robot served already, kNew for one served from now on,
  // kRefused (recording nothing) for a new one while max_robots are served.
  Heard hear(const std::string& robot_id, int64_t now_ns);

  bool serves(const std::string& robot_id) const;

  // Forgets the robots not heard from for longer than forget_after_ns before
  // `now_ns`; returns each one's id and how long it was silent (ns).
  struct Forgotten {
    std::string robot_id;
    int64_t silent_ns = 0;
  };
  std::vector<Forgotten> forgetSilent(int64_t now_ns);

  // Forgets `robot_id` now: another backbone serves it. False when it was
  // not served.
  bool forget(const std::string& robot_id);

  size_t size() const;

 private:
  const size_t max_robots_;
  const int64_t forget_after_ns_;
  mutable std::mutex mutex_;
  std::map<std::string, int64_t> last_heard_ns_;
};

}  // namespace lineloc
