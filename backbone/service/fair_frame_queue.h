// The LineSets a backbone has taken and not yet answered, at most one per
// robot, handed out fairly to the threads that answer them (frame_workers.h):
// a flooding robot (or many made-up ones) cannot make the others wait behind
// its frames.
//
// Latest only: a robot's newer frame supersedes its older one still
// waiting, which push() returns to be answered at once (FIX_BUSY): a robot
// whose frames come faster than they are answered gets answers for its
// newest ones, not later and later answers for all.
//
// One frame per robot at a time: a robot's frames are answered in order by
// its session, so pop() passes over a robot whose previous frame is still
// being answered (until done()).
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
//
// Back-pressure: a frame is useful to its robot until the robot's next one,
// a frame period T later (its last two stamps apart). A frame that would
// wait is refused at push() (answered FIX_BUSY at once, and the robot
// dead-reckons on) when it could not be answered within T:
//   W + S > T,  W = (sum_{q ahead} S_q + sum_{q in hand} max(0, S_q - e_q)) / n,
// where S is a robot's mean time per frame (exponentially weighted over its
// last frames, weight kFrameTimeWeight), the frames ahead are those LAS hands
// out first, e_q the time a frame in hand has been answered for, and n the
// threads answering. A robot not yet answered counts for nothing: a frame is
// refused only on evidence, and never one that would not wait.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "common/messages/messages.h"

namespace lineloc {

// Why a frame is answered FIX_BUSY without being localized (see above).
enum class FrameRefusal { kSuperseded, kLate };

class FairFrameQueue {
 public:
  // `workers`: the threads answering frames at once, at least one.
  explicit FairFrameQueue(int workers = 1, double service_half_life_s = 1.0);

  // Queues `line_set`, taken at `taken_ns` (steady clock), unless it would
  // be answered too late (see above).
  struct Pushed {
    // The robot's older frame that was waiting, superseded.
    std::optional<LineSetData> superseded;
    // `line_set` itself, not queued: it would be answered after its robot's
    // next frame.
    std::optional<LineSetData> late;
  };
  Pushed push(LineSetData line_set, int64_t taken_ns);

  // The next frame to answer (see above) and when it was taken; nullopt when
  // none waits whose robot has no frame in hand. Its robot's frame is in hand
  // until done().
  struct Taken {
    LineSetData line_set;
    int64_t taken_ns = 0;
  };
  std::optional<Taken> pop(int64_t now_ns);

  // Records that answering the frame of `robot_id` in hand took `service_ns`,
  // ending at `now_ns`.
  void done(const std::string& robot_id, int64_t service_ns, int64_t now_ns);

  // Frames waiting, and whether none waits and none is in hand.
  size_t size() const { return waiting_.size(); }
  bool idle() const { return waiting_.empty() && in_hand_.empty(); }

  // A robot's mean time per frame weighs its last one by this much.
  static constexpr double kFrameTimeWeight = 0.125;

 private:
  struct Service {
    // Attained service, decayed to updated_ns.
    double service_ns = 0.0;
    int64_t updated_ns = 0;
    // Mean time per frame (0 before the first) and frame period from the
    // last two stamps (0 before the second).
    double frame_ns = 0.0;
    int64_t period_ns = 0;
    int64_t last_stamp_ns = 0;
  };
  // `robot_id`'s attained service decayed to `now_ns` (ns).
  double serviceAt(const std::string& robot_id, int64_t now_ns) const;
  double frameTimeOf(const std::string& robot_id) const;
  // W of the rule above for a frame of `robot_id` pushed at `now_ns`.
  double expectedWaitNs(const std::string& robot_id, int64_t now_ns) const;
  // Records `line_set`'s stamp in its robot's frame period.
  void notePeriod(const LineSetData& line_set);
  // Forgets the service of robots with no frame waiting or in hand once it
  // has decayed below a microsecond, so that made-up robot ids do not
  // accumulate; at most once per half-life.
  void forgetNegligibleService(int64_t now_ns);

  const int workers_;
  const double half_life_ns_;
  std::map<std::string, Taken> waiting_;
  // The robots whose frame is being answered, and since when.
  std::map<std::string, int64_t> in_hand_;
  std::map<std::string, Service> service_;
  int64_t forgotten_ns_ = 0;
};

}  // namespace lineloc
