// C++ (Eigen) forms of lineloc's DDS messages and the conversions to and from
// the IDL structs. Conversions from the wire assume a message that passed
// common/messages/message_validator.h.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "common/camera/camera_calibration.h"
#include "common/geometry/pose.h"
#include "lineloc.h"

namespace lineloc {

// A straight segment in undistorted pixel coordinates (see lineloc.idl).
struct ImageSegment {
  Eigen::Vector2f start = Eigen::Vector2f::Zero();
  Eigen::Vector2f end = Eigen::Vector2f::Zero();
  Eigen::Matrix2f start_covariance = Eigen::Matrix2f::Identity();
  Eigen::Matrix2f end_covariance = Eigen::Matrix2f::Identity();
  float contrast = 0.0f;
  int polarity = 0;
};

struct ImageCorner {
  Eigen::Vector2f position = Eigen::Vector2f::Zero();
  Eigen::Matrix2f covariance = Eigen::Matrix2f::Identity();
  float strength = 0.0f;
};

struct LineSetData {
  std::string robot_id;
  uint32_t sequence_number = 0;
  int64_t stamp_ns = 0;
  PinholeCamera camera;
  std::vector<ImageSegment> segments;
  std::vector<ImageCorner> corners;
  PoseWithCovariance predicted_T_world_camera;
  // Camera height above the ground (m); 0: unknown (see lineloc.idl).
  double camera_height_m = 0.0;
};

struct StageTimingsNs {
  int64_t map = 0;
  int64_t visibility = 0;
  int64_t matching = 0;
  int64_t pose = 0;
  int64_t total = 0;
};

struct PoseFixData {
  std::string robot_id;
  uint32_t sequence_number = 0;
  int64_t stamp_ns = 0;
  PoseWithCovariance T_world_camera;
  lineloc_msg_FixStatus status = lineloc_msg_FIX_NO_MATCH_COMPUTED;
  uint32_t model_lines = 0;
  uint32_t inliers = 0;
  float residual_rms_px = 0.0f;
  StageTimingsNs timings;
  double unproven_position_sigma_m = 0.0;
  double unproven_rotation_sigma_rad = 0.0;
};

const char* toString(lineloc_msg_FixStatus status);

// Owns the arrays a lineloc_msg_LineSet points into, for as long as it is written.
class LineSetMessage {
 public:
  explicit LineSetMessage(const LineSetData& data);
  LineSetMessage(const LineSetMessage&) = delete;
  LineSetMessage& operator=(const LineSetMessage&) = delete;
  const lineloc_msg_LineSet& message() const { return message_; }

 private:
  std::vector<lineloc_msg_LineSegment> segments_;
  std::vector<lineloc_msg_Corner> corners_;
  lineloc_msg_LineSet message_{};
};

LineSetData fromMessage(const lineloc_msg_LineSet& message);
PoseFixData fromMessage(const lineloc_msg_PoseFix& message);
lineloc_msg_PoseFix toMessage(const PoseFixData& data);

lineloc_msg_Transform toMessage(const Eigen::Isometry3d& transform);
Eigen::Isometry3d fromMessage(const lineloc_msg_Transform& message);
lineloc_msg_PoseWithCovariance toMessage(const PoseWithCovariance& pose);
PoseWithCovariance fromMessage(const lineloc_msg_PoseWithCovariance& message);

// Copies a robot id into a bounded IDL string; throws when it does not fit.
void copyRobotId(const std::string& robot_id,
                 char (&destination)[lineloc_msg_ROBOT_ID_MAX_LENGTH + 1]);

}  // namespace lineloc
