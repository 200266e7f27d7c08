// A test street for enrichment: one building's wall at x = 10 m, facing the
// street (normal -x), 20 m long and 6 m high, with a window on it, seen by a
// camera that drives down the street at x = 0.
#pragma once

#include <Eigen/Geometry>
#include <random>
#include <vector>

#include "backbone/enrichment/surface_observations.h"

namespace lineloc::wall_drive {

inline const PinholeCamera kCamera{500, 500, 320, 240, 0, 640, 480};
inline constexpr int64_t kBuilding = 7;
inline constexpr double kWall_x = 10.0;
// The window's left side, outer edge, its frame 8 cm wide.
inline const Eigen::Vector3d kWindowSideStart(kWall_x, 5.0, 2.0);
inline const Eigen::Vector3d kWindowSideEnd(kWall_x, 5.0, 3.5);
inline const Eigen::Vector3d kFrameInnerStart(kWall_x, 5.08, 2.08);
inline const Eigen::Vector3d kFrameInnerEnd(kWall_x, 5.08, 3.42);
inline const Eigen::Vector3d kWindowTopStart(kWall_x, 5.0, 3.5);
inline const Eigen::Vector3d kWindowTopEnd(kWall_x, 6.2, 3.5);
// The wall's eave, a model line.
inline const Eigen::Vector3d kEaveStart(kWall_x, -5.0, 6.0);
inline const Eigen::Vector3d kEaveEnd(kWall_x, 15.0, 6.0);
// A lamp post 3 m in front of the wall, which the model lacks.
inline const Eigen::Vector3d kPostBottom(7.0, 3.0, 0.5);
inline const Eigen::Vector3d kPostTop(7.0, 3.0, 3.0);

inline std::vector<FaceRing> wallFaces() {
  // Counter-clockwise seen from the street (from -x): normal -x.
  return {{{kWall_x, 15.0, 0.0}, {kWall_x, -5.0, 0.0}, {kWall_x, -5.0, 6.0}, {kWall_x, 15.0, 6.0}}};
}

// The camera at (0, y, 1.6) looking along +x, turned yaw_rad about z, its
// pose known to about a centimetre and a twentieth of a degree.
inline PoseWithCovariance cameraAt(double y, double yaw_rad = 0.2) {
  Eigen::Matrix3d R_world_camera;
  R_world_camera << 0, 0, 1, -1, 0, 0, 0, -1, 0;  // camera z along +x, image y down
  PoseWithCovariance pose;
  pose.pose.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) * R_world_camera;
  pose.pose.translation() = Eigen::Vector3d(0.0, y, 1.6);
  pose.covariance = diagonalPoseCovariance(0.01, 0.001);
  return pose;
}

// The image segment of start -> end seen from the pose, endpoints moved by
// pixel noise of sigma_px; polarity +1: brighter left of start -> end.
inline ImageSegment segmentOf(const PoseWithCovariance& T_world_camera,
                              const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                              int polarity, double sigma_px, std::mt19937& random) {
  std::normal_distribution<double> noise(0.0, sigma_px);
  const Eigen::Isometry3d T_camera_world = T_world_camera.pose.inverse();
  ImageSegment segment;
  segment.start =
      (kCamera.project(T_camera_world * start) + Eigen::Vector2d(noise(random), noise(random)))
          .cast<float>();
  segment.end =
      (kCamera.project(T_camera_world * end) + Eigen::Vector2d(noise(random), noise(random)))
          .cast<float>();
  const float variance = static_cast<float>(std::max(sigma_px * sigma_px, 0.25));
  segment.start_covariance = Eigen::Matrix2f::Identity() * variance;
  segment.end_covariance = segment.start_covariance;
  segment.polarity = polarity;
  segment.contrast = 20.0f;
  return segment;
}

// What the frame from `T_world_camera` shows: the window's side, its frame's
// inner edge (bright on the other side), its top, the eave and the post.
inline EnrichmentFrame frameAt(const PoseWithCovariance& T_world_camera, double sigma_px,
                               std::mt19937& random) {
  EnrichmentFrame frame;
  frame.robot_id = "r1";
  frame.camera = kCamera;
  frame.T_world_camera = T_world_camera;
  frame.segments = {
      segmentOf(T_world_camera, kWindowSideStart, kWindowSideEnd, 1, sigma_px, random),
      segmentOf(T_world_camera, kFrameInnerStart, kFrameInnerEnd, -1, sigma_px, random),
      segmentOf(T_world_camera, kWindowTopStart, kWindowTopEnd, 1, sigma_px, random),
      segmentOf(T_world_camera, kEaveStart + Eigen::Vector3d(0, 12, 0), kEaveEnd, 1, sigma_px,
                random),
      segmentOf(T_world_camera, kPostBottom, kPostTop, 1, sigma_px, random)};
  VisibleSegment eave;
  eave.model_line_id = 1;
  eave.start_world = kEaveStart + Eigen::Vector3d(0, 10, 0);
  eave.end_world = kEaveEnd;
  frame.visible = {eave};
  return frame;
}

// Distance of `point` from the line through start and end.
inline double distanceFromLine(const Eigen::Vector3d& point, const Eigen::Vector3d& start,
                               const Eigen::Vector3d& end) {
  const Eigen::Vector3d direction = (end - start).normalized();
  const Eigen::Vector3d offset = point - start;
  return (offset - offset.dot(direction) * direction).norm();
}

}  // namespace lineloc::wall_drive
