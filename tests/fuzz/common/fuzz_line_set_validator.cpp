// Fuzz target: the validator every receiver runs on a LineSet, fed arbitrary
// field values (the bytes are the struct's scalar fields and sequence contents).
// Whatever it accepts must convert to finite Eigen values.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "common/messages/message_validator.h"
#include "common/messages/messages.h"

namespace {

template <typename T>
void take(T& value, const uint8_t*& data, size_t& size) {
  const size_t n = std::min(sizeof(T), size);
  if (n == 0)
    return;
  std::memcpy(&value, data, n);
  data += n;
  size -= n;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lineloc_msg_LineSet message{};
  take(message.robot_id, data, size);
  message.robot_id[lineloc_msg_ROBOT_ID_MAX_LENGTH] = '\0';
  take(message.sequence_number, data, size);
  take(message.stamp_ns, data, size);
  take(message.camera, data, size);
  take(message.predicted_T_world_camera, data, size);
  take(message.camera_height_m, data, size);
  uint8_t segment_count = 0;
  uint8_t corner_count = 0;
  take(segment_count, data, size);
  take(corner_count, data, size);
  std::vector<lineloc_msg_LineSegment> segments(segment_count);
  std::vector<lineloc_msg_Corner> corners(corner_count);
  for (auto& segment : segments)
    take(segment, data, size);
  for (auto& corner : corners)
    take(corner, data, size);
  message.segments = {segment_count, segment_count, segments.data(), false};
  message.corners = {corner_count, corner_count, corners.data(), false};

  lineloc::MessageLimits limits;
  limits.max_segments = 200;
  if (lineloc::findLineSetError(message, limits)) {
    return 0;
  }
  const lineloc::LineSetData line_set = lineloc::fromMessage(message);
  const bool finite = line_set.predicted_T_world_camera.pose.matrix().allFinite() &&
                      std::all_of(line_set.segments.begin(), line_set.segments.end(),
                                  [](const lineloc::ImageSegment& s) {
                                    return s.start.allFinite() && s.end.allFinite() &&
                                           s.start_covariance.allFinite() &&
                                           s.end_covariance.allFinite();
                                  });
  if (!finite || line_set.segments.size() > limits.max_segments) {
    __builtin_trap();
  }
  return 0;
}
