#include "common/messages/messages.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace lineloc {
namespace {

void toPacked(const Eigen::Matrix2f& covariance, float (&packed)[3]) {
  packed[0] = covariance(0, 0);
  packed[1] = covariance(0, 1);
  packed[2] = covariance(1, 1);
}

Eigen::Matrix2f fromPacked(const float (&packed)[3]) {
  Eigen::Matrix2f covariance;
  covariance << packed[0], packed[1], packed[1], packed[2];
  return covariance;
}

lineloc_msg_LineSegment toMessage(const ImageSegment& segment) {
  lineloc_msg_LineSegment message{};
  message.start[0] = segment.start.x();
  message.start[1] = segment.start.y();
  message.end[0] = segment.end.x();
  message.end[1] = segment.end.y();
  toPacked(segment.start_covariance, message.start_covariance);
  toPacked(segment.end_covariance, message.end_covariance);
  message.contrast = segment.contrast;
  message.polarity = static_cast<int16_t>(segment.polarity);
  return message;
}

ImageSegment fromMessage(const lineloc_msg_LineSegment& message) {
  ImageSegment segment;
  segment.start = {message.start[0], message.start[1]};
  segment.end = {message.end[0], message.end[1]};
  segment.start_covariance = fromPacked(message.start_covariance);
  segment.end_covariance = fromPacked(message.end_covariance);
  segment.contrast = message.contrast;
  segment.polarity = message.polarity;
  return segment;
}

lineloc_msg_Corner toMessage(const ImageCorner& corner) {
  lineloc_msg_Corner message{};
  message.position[0] = corner.position.x();
  message.position[1] = corner.position.y();
  toPacked(corner.covariance, message.covariance);
  message.strength = corner.strength;
  return message;
}

ImageCorner fromMessage(const lineloc_msg_Corner& message) {
  ImageCorner corner;
  corner.position = {message.position[0], message.position[1]};
  corner.covariance = fromPacked(message.covariance);
  corner.strength = message.strength;
  return corner;
}

lineloc_msg_CameraIntrinsics toMessage(const PinholeCamera& camera) {
  lineloc_msg_CameraIntrinsics message{};
  message.fx = camera.fx;
  message.fy = camera.fy;
  message.cx = camera.cx;
  message.cy = camera.cy;
  message.width = static_cast<uint16_t>(camera.width);
  message.height = static_cast<uint16_t>(camera.height);
  return message;
}

PinholeCamera fromMessage(const lineloc_msg_CameraIntrinsics& message) {
  PinholeCamera camera;
  camera.fx = message.fx;
  camera.fy = message.fy;
  camera.cx = message.cx;
  camera.cy = message.cy;
  camera.width = message.width;
  camera.height = message.height;
  return camera;
}

lineloc_msg_StageTimings toMessage(const StageTimingsNs& timings) {
  return {timings.map, timings.visibility, timings.matching, timings.pose, timings.total};
}

StageTimingsNs fromMessage(const lineloc_msg_StageTimings& message) {
  return {message.map_ns, message.visibility_ns, message.matching_ns, message.pose_ns,
          message.total_ns};
}

}  // namespace

const char* toString(lineloc_msg_FixStatus status) {
  switch (status) {
    case lineloc_msg_FIX_OK:
      return "ok";
    case lineloc_msg_FIX_NO_MATCH_COMPUTED:
      return "no_match_computed";
    case lineloc_msg_FIX_NO_MAP_LINES:
      return "no_map_lines";
    case lineloc_msg_FIX_TOO_FEW_MATCHES:
      return "too_few_matches";
    case lineloc_msg_FIX_DEGENERATE:
      return "degenerate";
    case lineloc_msg_FIX_AMBIGUOUS:
      return "ambiguous";
    case lineloc_msg_FIX_DIVERGED:
      return "diverged";
    case lineloc_msg_FIX_INTERNAL_ERROR:
      return "internal_error";
    case lineloc_msg_FIX_BUSY:
      return "busy";
  }
  return "unknown";
}

void copyRobotId(const std::string& robot_id,
                 char (&destination)[lineloc_msg_ROBOT_ID_MAX_LENGTH + 1]) {
  if (robot_id.size() > lineloc_msg_ROBOT_ID_MAX_LENGTH) {
    throw std::invalid_argument(fmt::format("robot id '{}' is longer than {} characters", robot_id,
                                            lineloc_msg_ROBOT_ID_MAX_LENGTH));
  }
  std::memset(destination, 0, sizeof(destination));
  std::memcpy(destination, robot_id.data(), robot_id.size());
}

lineloc_msg_Transform toMessage(const Eigen::Isometry3d& transform) {
  lineloc_msg_Transform message{};
  const Eigen::Vector3d t = transform.translation();
  const Eigen::Quaterniond q(transform.linear());
  std::copy(t.data(), t.data() + 3, message.translation);
  std::copy(q.coeffs().data(), q.coeffs().data() + 4, message.rotation_xyzw);
  return message;
}

Eigen::Isometry3d fromMessage(const lineloc_msg_Transform& message) {
  const Eigen::Map<const Eigen::Vector3d> t(message.translation);
  const Eigen::Map<const Eigen::Quaterniond> q(message.rotation_xyzw);
  return makePose(t, q);
}

lineloc_msg_PoseWithCovariance toMessage(const PoseWithCovariance& pose) {
  lineloc_msg_PoseWithCovariance message{};
  message.pose = toMessage(pose.pose);
  Eigen::Map<Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(message.covariance) = pose.covariance;
  return message;
}

PoseWithCovariance fromMessage(const lineloc_msg_PoseWithCovariance& message) {
  PoseWithCovariance pose;
  pose.pose = fromMessage(message.pose);
  pose.covariance =
      Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(message.covariance);
  return pose;
}

LineSetMessage::LineSetMessage(const LineSetData& data) {
  segments_.reserve(data.segments.size());
  for (const ImageSegment& segment : data.segments) {
    segments_.push_back(toMessage(segment));
  }
  corners_.reserve(data.corners.size());
  for (const ImageCorner& corner : data.corners) {
    corners_.push_back(toMessage(corner));
  }
  copyRobotId(data.robot_id, message_.robot_id);
  message_.sequence_number = data.sequence_number;
  message_.stamp_ns = data.stamp_ns;
  message_.camera = toMessage(data.camera);
  message_.segments = {static_cast<uint32_t>(segments_.size()),
                       static_cast<uint32_t>(segments_.size()), segments_.data(), false};
  message_.corners = {static_cast<uint32_t>(corners_.size()),
                      static_cast<uint32_t>(corners_.size()), corners_.data(), false};
  message_.predicted_T_world_camera = toMessage(data.predicted_T_world_camera);
  message_.camera_height_m = data.camera_height_m;
}

LineSetData fromMessage(const lineloc_msg_LineSet& message) {
  LineSetData data;
  data.robot_id = message.robot_id;
  data.sequence_number = message.sequence_number;
  data.stamp_ns = message.stamp_ns;
  data.camera = fromMessage(message.camera);
  data.segments.reserve(message.segments._length);
  for (uint32_t i = 0; i < message.segments._length; ++i) {
    data.segments.push_back(fromMessage(message.segments._buffer[i]));
  }
  data.corners.reserve(message.corners._length);
  for (uint32_t i = 0; i < message.corners._length; ++i) {
    data.corners.push_back(fromMessage(message.corners._buffer[i]));
  }
  data.predicted_T_world_camera = fromMessage(message.predicted_T_world_camera);
  data.camera_height_m = message.camera_height_m;
  return data;
}

lineloc_msg_PoseFix toMessage(const PoseFixData& data) {
  lineloc_msg_PoseFix message{};
  copyRobotId(data.robot_id, message.robot_id);
  message.sequence_number = data.sequence_number;
  message.stamp_ns = data.stamp_ns;
  message.T_world_camera = toMessage(data.T_world_camera);
  message.status = data.status;
  message.model_lines = data.model_lines;
  message.inliers = data.inliers;
  message.residual_rms_px = data.residual_rms_px;
  message.timings = toMessage(data.timings);
  message.unproven_position_sigma_m = data.unproven_position_sigma_m;
  message.unproven_rotation_sigma_rad = data.unproven_rotation_sigma_rad;
  return message;
}

PoseFixData fromMessage(const lineloc_msg_PoseFix& message) {
  PoseFixData data;
  data.robot_id = message.robot_id;
  data.sequence_number = message.sequence_number;
  data.stamp_ns = message.stamp_ns;
  data.T_world_camera = fromMessage(message.T_world_camera);
  data.status = message.status;
  data.model_lines = message.model_lines;
  data.inliers = message.inliers;
  data.residual_rms_px = message.residual_rms_px;
  data.timings = fromMessage(message.timings);
  data.unproven_position_sigma_m = message.unproven_position_sigma_m;
  data.unproven_rotation_sigma_rad = message.unproven_rotation_sigma_rad;
  return data;
}

}  // namespace lineloc
