// The LineSets a backbone has taken and not yet answered, at most one per
// robot, handed out fairly: a flooding robot (or many made-up ones) cannot
// make the others wait behind its frames.
//
// Latest only: a robot's newer frame supersedes its older one still
// waiting, which push() returns to be answered at once (FIX_BUSY): a robot
// whose frames come faster than they are answered gets answers for its
// newest ones, not later and later answers for all.
//
// Least attained service (LAS; Rai, Urvoy-Keller & Biersack, "Analysis of
// LAS scheduling for job size distributions with high variance", SIGMETRICS
// 2003), per robot: pop() hands out the frame of the robot that has had the
// least handling time recently, its service s decayed exponentially with
// half-life h,
//   s <- s 2^(-dt/h) + t_handled,
// earliest arrival first among equals. A robot at 10 Hz with a few hundred
// segments is answered before one sending 4,096-segment frames at 100 Hz,
// which waits its turn, yet the backbone never idles while a frame waits.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "common/messages/messages.h"

namespace lineloc {

class FairFrameQueue {
 public:
  explicit FairFrameQueue(double service_half_life_s = 1.0);

  // Queues `line_set`, taken at `taken_ns` (steady clock); returns the frame
  // of the same robot it supersedes, if one waited.
  std::optional<LineSetData> push(LineSetData line_set, int64_t taken_ns);

  // The next frame to answer (see above) and when it was taken; nullopt when none waits.
  struct Taken {
    LineSetData line_set;
    int64_t taken_ns = 0;
  };
  std::optional<Taken> pop(int64_t now_ns);

  // Records that answering a frame of `robot_id` took `service_ns`, ending at `now_ns`.
  void charge(const std::string& robot_id, int64_t service_ns, int64_t now_ns);

  bool empty() const { return waiting_.empty(); }
  size_t size() const { return waiting_.size(); }

 private:
  // `robot_id`'s service decayed to `now_ns` (ns).
  double serviceAt(const std::string& robot_id, int64_t now_ns) const;
  // Forgets the service of robots with no frame waiting once it has decayed
  // below a microsecond, so that made-up robot ids do not accumulate; at
  // most once per half-life.
  void forgetNegligibleService(int64_t now_ns);

  struct Service {
    double service_ns = 0.0;
    int64_t updated_ns = 0;
  };
  const double half_life_ns_;
  std::map<std::string, Taken> waiting_;
  std::map<std::string, Service> service_;
  int64_t forgotten_ns_ = 0;
};

}  // namespace lineloc
