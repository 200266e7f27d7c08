// The view frustum of a pinhole camera at a pose: the world points the camera
// images between a near and a far depth (the part of the model the matcher can
// see, paper §3.1-3.2), as six half-spaces n . x + d >= 0 in the world frame.
//
// The planes are common/camera/camera_frustum.h's, moved from the camera frame
// to the world with T_world_camera = [R | t] as n_w = R n_c, d_w = d - n_w . t;
// a segment meets the frustum when Cyrus-Beck clipping leaves some of it.
#pragma once

#include <Eigen/Geometry>
#include <array>

#include "common/camera/camera_calibration.h"
#include "common/camera/camera_frustum.h"

namespace lineloc::db {

class ViewFrustum {
 public:
  // Throws std::invalid_argument when the pose is not finite, the camera has
  // no positive focal lengths and image size, or not 0 < near_m < far_m.
  ViewFrustum(const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera, double near_m,
              double far_m);

  // True when some point of the segment a-b (world frame) lies in the frustum.
  bool meetsSegment(const Eigen::Vector3d& a_world, const Eigen::Vector3d& b_world) const;

  // The axis-aligned box around the frustum's eight corners (world frame).
  const Eigen::AlignedBox3d& boundsWorld() const { return bounds_world_; }

 private:
  HalfSpaces planes_world_;
  Eigen::AlignedBox3d bounds_world_;
};

}  // namespace lineloc::db
