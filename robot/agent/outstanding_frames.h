// The frames a robot has sent and not yet had answered. An answer (PoseFix)
// is taken once, for the frame whose sequence number and stamp it carries: a
// restarted robot numbers its frames from 0 again, and the backbone keeps its
// last answers a moment for late readers (common/messages/topics.h), so an
// answer to the run before can name a frame of this run.
//
// An answer's exposure -> fix latency and its legs (fixLatencyOf): the
// robot's own intervals are read on its steady clock, so a wall clock that is
// stepped or slewed meanwhile (NTP, chrony disciplined by GPS time) does not
// enter them; only the legs to and from the backbone compare the robot's wall
// clock with the backbone's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_map>

namespace lineloc {

class OutstandingFrames {
 public:
  struct Frame {
    int64_t stamp_ns = 0;
    int64_t exposure_steady_ns = 0;
    int64_t sent_steady_ns = 0;
    int64_t sent_wall_ns = 0;
  };

  void expect(uint32_t sequence_number, const Frame& frame);

  // The frame an answer with this sequence number and stamp is for, no longer
  // outstanding; nullopt when no such frame waits for one.
  std::optional<Frame> take(uint32_t sequence_number, int64_t stamp_ns);

  bool answered(uint32_t sequence_number) const { return frames_.count(sequence_number) == 0; }
  size_t size() const { return frames_.size(); }

 private:
  std::unordered_map<uint32_t, Frame> frames_;
};

// total = front_end + to_backbone + backbone + back.
struct FixLatency {
  int64_t total_ns = 0;
  int64_t front_end_ns = 0;    // exposure -> LineSet written
  int64_t to_backbone_ns = 0;  // LineSet written -> the backbone starts on it
  int64_t backbone_ns = 0;     // the backbone's own total
  int64_t back_ns = 0;         // PoseFix written -> received
};

// `received_*`: when the answer came, on the robot's clocks; `written_wall_ns`:
// when the backbone wrote it, on its wall clock; `backbone_ns`: its timings' total.
FixLatency fixLatencyOf(const OutstandingFrames::Frame& frame, int64_t received_steady_ns,
                        int64_t received_wall_ns, int64_t written_wall_ns, int64_t backbone_ns);

}  // namespace lineloc
