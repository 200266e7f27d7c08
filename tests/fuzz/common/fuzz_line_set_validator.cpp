// Fuzz target: the validator every receiver runs on a LineSet, fed arbitrary
// field values (the bytes are the struct's scalar fields and sequence contents).
// Whatever it accepts must convert to finite Eigen values.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/messages/message_validator.h"
#include "common/messages/messages.h"
#include "tests/fuzz/common/struct_fields.h"

using lineloc::fuzz::takeField;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lineloc_msg_LineSet message{};
  takeField(message.robot_id, data, size);
  message.robot_id[lineloc_msg_ROBOT_ID_MAX_LENGTH] = '\0';
  takeField(message.sequence_number, data, size);
  takeField(message.stamp_ns, data, size);
  takeField(message.camera, data, size);
  takeField(message.predicted_T_world_camera, data, size);
  takeField(message.camera_height_m, data, size);
  uint8_t segment_count = 0;
  uint8_t corner_count = 0;
  takeField(segment_count, data, size);
  takeField(corner_count, data, size);
  std::vector<lineloc_msg_LineSegment> segments(segment_count);
  std::vector<lineloc_msg_Corner> corners(corner_count);
  for (auto& segment : segments)
    takeField(segment, data, size);
  for (auto& corner : corners)
    takeField(corner, data, size);
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
