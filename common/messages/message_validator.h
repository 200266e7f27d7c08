// The one validator every receiver of a lineloc message runs before using it.
//
// It checks what the wire format cannot: finite numbers, unit quaternions,
// covariances that can be covariances, values inside their bounds, sequence
// lengths inside the receiver's configured limits, and the robot id format
// [A-Za-z0-9][A-Za-z0-9_.-]*. A message that fails is to be dropped and
// counted; the returned text names the field and index at fault.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "lineloc.h"

namespace lineloc {

struct MessageLimits {
  uint32_t max_segments = 2048;
  uint32_t max_corners = 2048;
  // The LineSet's camera image: at most this many pixels a side, and in all
  // (the backbone's work per frame grows with the image's area).
  uint32_t max_camera_side_px = 8192;
  double max_camera_megapixels = 32.0;
  // Undistorted coordinates may leave the image by this fraction of its size.
  double image_margin_fraction = 0.5;
};

bool isValidRobotId(std::string_view robot_id);
// The same pattern, at most BACKBONE_NAME_MAX_LENGTH characters.
bool isValidBackboneName(std::string_view name);

// Each returns nullopt for a valid message, or what is wrong and where.
std::optional<std::string> findLineSetError(const lineloc_msg_LineSet& message,
                                            const MessageLimits& limits);
std::optional<std::string> findPoseFixError(const lineloc_msg_PoseFix& message);
std::optional<std::string> findRobotStateError(const lineloc_msg_RobotState& message);
// At most kMaxAgreeingProofs agreeing proofs; finite distances, the rival's
// non-negative; at most MAX_HANDED_HYPOTHESES hypotheses, each finite with a
// unit quaternion.
std::optional<std::string> findTrackingHandoverError(const lineloc_msg_TrackingHandover& message);
inline constexpr uint32_t kMaxAgreeingProofs = 1'000'000;

}  // namespace lineloc
