#include "common/messages/message_validator.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstring>

namespace lineloc {
namespace {

constexpr double kQuaternionNormTolerance = 1e-3;
constexpr double kCovarianceSymmetryTolerance = 1e-6;
// No ground robot carries its camera higher (m).
constexpr double kMaxCameraHeightM = 100.0;

using Error = std::optional<std::string>;

template <typename T, size_t N>
bool allFinite(const T (&values)[N]) {
  for (const T value : values) {
    if (!std::isfinite(value)) {
      return false;
    }
  }
  return true;
}

// A packed 2x2 covariance (xx, xy, yy) must be finite and positive semi-definite.
Error checkCovariance2(const float (&c)[3], const std::string& where) {
  if (!allFinite(c)) {
    return where + ": covariance is not finite";
  }
  if (c[0] < 0.0f || c[2] < 0.0f || c[0] * c[2] - c[1] * c[1] < -1e-6f * (c[0] + c[2])) {
    return where + ": covariance is not positive semi-definite";
  }
  return std::nullopt;
}

Error checkTransform(const lineloc_msg_Transform& transform, const std::string& where) {
  if (!allFinite(transform.translation) || !allFinite(transform.rotation_xyzw)) {
    return where + ": not finite";
  }
  const double* q = transform.rotation_xyzw;
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (std::abs(norm - 1.0) > kQuaternionNormTolerance) {
    return fmt::format("{}: quaternion norm {:.6f} is not 1", where, norm);
  }
  return std::nullopt;
}

Error checkPose(const lineloc_msg_PoseWithCovariance& pose, const std::string& where) {
  if (Error e = checkTransform(pose.pose, where))
    return e;
  if (!allFinite(pose.covariance)) {
    return where + ": not finite";
  }
  for (int row = 0; row < 6; ++row) {
    if (pose.covariance[row * 6 + row] < 0.0) {
      return fmt::format("{}: covariance diagonal {} is negative", where, row);
    }
    for (int col = row + 1; col < 6; ++col) {
      const double a = pose.covariance[row * 6 + col];
      const double b = pose.covariance[col * 6 + row];
      if (std::abs(a - b) > kCovarianceSymmetryTolerance * (1.0 + std::abs(a))) {
        return fmt::format("{}: covariance is not symmetric at ({}, {})", where, row, col);
      }
    }
  }
  return std::nullopt;
}

// The unproven part of a fix's covariance lies within it: each variance at
// most the covariance's diagonal there.
Error checkUnprovenPart(const lineloc_msg_PoseFix& message) {
  const double sigmas[2] = {message.unproven_position_sigma_m, message.unproven_rotation_sigma_rad};
  const char* names[2] = {"unproven_position_sigma_m", "unproven_rotation_sigma_rad"};
  for (int block = 0; block < 2; ++block) {
    if (!(std::isfinite(sigmas[block]) && sigmas[block] >= 0.0)) {
      return fmt::format("{} {} must be finite and non-negative", names[block], sigmas[block]);
    }
    for (int axis = 3 * block; axis < 3 * block + 3; ++axis) {
      const double variance = message.T_world_camera.covariance[axis * 6 + axis];
      if (sigmas[block] * sigmas[block] > variance) {
        return fmt::format("{} {} exceeds T_world_camera's sigma {} on axis {}", names[block],
                           sigmas[block], std::sqrt(variance), axis);
      }
    }
  }
  return std::nullopt;
}

Error checkRobotId(const char* robot_id) {
  if (!isValidRobotId(robot_id)) {
    return fmt::format("robot_id '{}' is not of the form [A-Za-z0-9][A-Za-z0-9_.-]*",
                       std::string(robot_id, strnlen(robot_id, lineloc_msg_ROBOT_ID_MAX_LENGTH)));
  }
  return std::nullopt;
}

struct PixelBounds {
  float min_x, max_x, min_y, max_y;
  bool contains(const float (&p)[2]) const {
    return p[0] >= min_x && p[0] <= max_x && p[1] >= min_y && p[1] <= max_y;
  }
};

Error checkPoint(const float (&p)[2], const PixelBounds& bounds, const std::string& where) {
  if (!allFinite(p)) {
    return where + ": not finite";
  }
  if (!bounds.contains(p)) {
    return fmt::format("{}: ({}, {}) is outside the image", where, p[0], p[1]);
  }
  return std::nullopt;
}

Error checkSegment(const lineloc_msg_LineSegment& s, const PixelBounds& bounds, uint32_t index) {
  const std::string where = fmt::format("segments[{}]", index);
  if (Error e = checkPoint(s.start, bounds, where + ".start"))
    return e;
  if (Error e = checkPoint(s.end, bounds, where + ".end"))
    return e;
  if (Error e = checkCovariance2(s.start_covariance, where + ".start"))
    return e;
  if (Error e = checkCovariance2(s.end_covariance, where + ".end"))
    return e;
  if (!std::isfinite(s.contrast) || s.contrast < 0.0f) {
    return where + ": contrast must be finite and non-negative";
  }
  if (s.polarity < -1 || s.polarity > 1) {
    return fmt::format("{}: polarity {} is not -1, 0 or 1", where, s.polarity);
  }
  return std::nullopt;
}

Error checkCorner(const lineloc_msg_Corner& c, const PixelBounds& bounds, uint32_t index) {
  const std::string where = fmt::format("corners[{}]", index);
  if (Error e = checkPoint(c.position, bounds, where + ".position"))
    return e;
  if (Error e = checkCovariance2(c.covariance, where))
    return e;
  if (!std::isfinite(c.strength)) {
    return where + ": strength is not finite";
  }
  return std::nullopt;
}

Error checkCamera(const lineloc_msg_CameraIntrinsics& camera, const MessageLimits& limits) {
  const double values[] = {camera.fx, camera.fy, camera.cx, camera.cy};
  if (!allFinite(values) || camera.fx <= 0.0 || camera.fy <= 0.0) {
    return std::string("camera: intrinsics must be finite with positive focal lengths");
  }
  if (camera.width == 0 || camera.height == 0) {
    return std::string("camera: image size is zero");
  }
  if (camera.width > limits.max_camera_side_px) {
    return fmt::format("camera.width {} px exceeds the limit of {} px", camera.width,
                       limits.max_camera_side_px);
  }
  if (camera.height > limits.max_camera_side_px) {
    return fmt::format("camera.height {} px exceeds the limit of {} px", camera.height,
                       limits.max_camera_side_px);
  }
  const double megapixels = 1e-6 * camera.width * camera.height;
  if (megapixels > limits.max_camera_megapixels) {
    return fmt::format(
        "camera.width x camera.height {} x {} px ({:.1f} megapixels) exceed the "
        "limit of {} megapixels",
        camera.width, camera.height, megapixels, limits.max_camera_megapixels);
  }
  return std::nullopt;
}

// The integer a received enum field holds: a peer may send any 32-bit value,
// and loading one outside the enumerators through the enum type is undefined.
template <typename Enum>
int32_t rawEnumValue(const Enum& field) {
  static_assert(sizeof(Enum) == sizeof(int32_t), "IDL enums are 32-bit");
  int32_t raw = 0;
  std::memcpy(&raw, &field, sizeof raw);
  return raw;
}

// [A-Za-z0-9][A-Za-z0-9_.-]*, at most `max_length` characters.
bool isValidName(std::string_view name, size_t max_length) {
  if (name.empty() || name.size() > max_length ||
      !std::isalnum(static_cast<unsigned char>(name.front()))) {
    return false;
  }
  for (const char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.') {
      return false;
    }
  }
  return true;
}

}  // namespace

bool isValidRobotId(std::string_view robot_id) {
  return isValidName(robot_id, lineloc_msg_ROBOT_ID_MAX_LENGTH);
}

bool isValidBackboneName(std::string_view name) {
  return isValidName(name, lineloc_msg_BACKBONE_NAME_MAX_LENGTH);
}

std::optional<std::string> findLineSetError(const lineloc_msg_LineSet& message,
                                            const MessageLimits& limits) {
  if (Error e = checkRobotId(message.robot_id))
    return e;
  if (message.stamp_ns <= 0) {
    return fmt::format("stamp_ns {} is not positive", message.stamp_ns);
  }
  if (Error e = checkCamera(message.camera, limits))
    return e;
  if (message.segments._length > limits.max_segments) {
    return fmt::format("{} segments exceed the limit of {}", message.segments._length,
                       limits.max_segments);
  }
  if (message.corners._length > limits.max_corners) {
    return fmt::format("{} corners exceed the limit of {}", message.corners._length,
                       limits.max_corners);
  }
  const float margin_x = static_cast<float>(limits.image_margin_fraction * message.camera.width);
  const float margin_y = static_cast<float>(limits.image_margin_fraction * message.camera.height);
  const PixelBounds bounds{-margin_x, message.camera.width + margin_x, -margin_y,
                           message.camera.height + margin_y};
  for (uint32_t i = 0; i < message.segments._length; ++i) {
    if (Error e = checkSegment(message.segments._buffer[i], bounds, i))
      return e;
  }
  for (uint32_t i = 0; i < message.corners._length; ++i) {
    if (Error e = checkCorner(message.corners._buffer[i], bounds, i))
      return e;
  }
  if (!(message.camera_height_m >= 0.0 && message.camera_height_m <= kMaxCameraHeightM)) {
    return fmt::format("camera_height_m {} is outside [0, {}]", message.camera_height_m,
                       kMaxCameraHeightM);
  }
  return checkPose(message.predicted_T_world_camera, "predicted_T_world_camera");
}

std::optional<std::string> findPoseFixError(const lineloc_msg_PoseFix& message) {
  if (Error e = checkRobotId(message.robot_id))
    return e;
  const int32_t status = rawEnumValue(message.status);
  if (status < lineloc_msg_FIX_OK || status > lineloc_msg_FIX_BUSY) {
    return fmt::format("status {} is unknown", status);
  }
  if (!std::isfinite(message.residual_rms_px) || message.residual_rms_px < 0.0f) {
    return std::string("residual_rms_px must be finite and non-negative");
  }
  if (Error e = checkPose(message.T_world_camera, "T_world_camera"))
    return e;
  return checkUnprovenPart(message);
}

std::optional<std::string> findRobotStateError(const lineloc_msg_RobotState& message) {
  if (Error e = checkRobotId(message.robot_id))
    return e;
  if (!allFinite(message.velocity_world) || !allFinite(message.velocity_covariance)) {
    return std::string("velocity: not finite");
  }
  const int32_t health = rawEnumValue(message.health);
  if (health < lineloc_msg_HEALTH_INITIALISING || health > lineloc_msg_HEALTH_LOST) {
    return fmt::format("health {} is unknown", health);
  }
  return checkPose(message.T_world_body, "T_world_body");
}

std::optional<std::string> findTrackingHandoverError(const lineloc_msg_TrackingHandover& message) {
  if (Error e = checkRobotId(message.robot_id))
    return e;
  if (!isValidBackboneName(message.backbone)) {
    return fmt::format("backbone '{}' is not of the form [A-Za-z0-9][A-Za-z0-9_.-]*",
                       message.backbone);
  }
  if (message.agreeing_proofs > kMaxAgreeingProofs) {
    return fmt::format("agreeing_proofs {} exceeds {}", message.agreeing_proofs,
                       kMaxAgreeingProofs);
  }
  if (!std::isfinite(message.proof_due_in_m)) {
    return std::string("proof_due_in_m is not finite");
  }
  if (!(std::isfinite(message.rival_position_m) && message.rival_position_m >= 0.0 &&
        std::isfinite(message.rival_rotation_rad) && message.rival_rotation_rad >= 0.0)) {
    return fmt::format("rival {} m, {} rad must be finite and non-negative",
                       message.rival_position_m, message.rival_rotation_rad);
  }
  if (message.hypothesis_count > lineloc_msg_MAX_HANDED_HYPOTHESES) {
    return fmt::format("hypothesis_count {} exceeds {}", message.hypothesis_count,
                       lineloc_msg_MAX_HANDED_HYPOTHESES);
  }
  for (uint32_t i = 0; i < message.hypothesis_count; ++i) {
    if (Error e = checkTransform(message.hypotheses_T_prediction_camera[i],
                                 fmt::format("hypotheses_T_prediction_camera[{}]", i)))
      return e;
  }
  return std::nullopt;
}

}  // namespace lineloc
