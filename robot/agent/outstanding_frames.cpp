#include "robot/agent/outstanding_frames.h"

namespace lineloc {

void OutstandingFrames::expect(uint32_t sequence_number, const Frame& frame) {
  frames_[sequence_number] = frame;
}

std::optional<OutstandingFrames::Frame> OutstandingFrames::take(uint32_t sequence_number,
                                                                int64_t stamp_ns) {
  const auto found = frames_.find(sequence_number);
  if (found == frames_.end() || found->second.stamp_ns != stamp_ns) {
    return std::nullopt;
  }
  const Frame frame = found->second;
  frames_.erase(found);
  return frame;
}

}  // namespace lineloc
