// The frames a robot has sent and not yet had answered. An answer (PoseFix)
// is taken once, for the frame whose sequence number and stamp it carries: a
// restarted robot numbers its frames from 0 again, and the backbone keeps its
// last answers a moment for late readers (common/messages/topics.h), so an
// answer to the run before can name a frame of this run.
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
    int64_t exposure_wall_ns = 0;
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

}  // namespace lineloc
