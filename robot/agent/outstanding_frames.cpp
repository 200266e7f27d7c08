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

FixLatency fixLatencyOf(const OutstandingFrames::Frame& frame, int64_t received_steady_ns,
                        int64_t received_wall_ns, int64_t written_wall_ns, int64_t backbone_ns) {
  FixLatency latency;
  latency.total_ns = received_steady_ns - frame.exposure_steady_ns;
  latency.front_end_ns = frame.sent_steady_ns - frame.exposure_steady_ns;
  latency.to_backbone_ns = written_wall_ns - frame.sent_wall_ns - backbone_ns;
  latency.backbone_ns = backbone_ns;
  latency.back_ns = received_wall_ns - written_wall_ns;
  return latency;
}

}  // namespace lineloc
