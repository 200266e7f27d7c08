// The view frustum of a pinhole camera at a pose: the world points the camera
// images between a near and a far depth (the part of the model the matcher can
// see, paper §3.1-3.2), as six half-spaces n . x + d >= 0 in the world frame.
//
// In the camera frame (OpenCV: x right, y down, z forward) the side planes pass
// through the optical centre and the rays of two adjacent image corners,
//   r(u, v) = K^-1 [u v 1]^T:  y = (v - cy) / fy,  x = (u - cx - skew y) / fx,
// with normal r_i x r_(i+1) turned towards the centre ray; near and far are
// z >= near and z <= far. A plane (n_c, d) moves to the world frame with
// T_world_camera = [R | t] as n_w = R n_c, d_w = d - n_w . t.
//
// A segment a + s (b - a), s in [0, 1], meets the frustum when Cyrus-Beck
// clipping (Cyrus & Beck, "Generalized two- and three-dimensional clipping",
// 1978) against the six half-spaces leaves a non-empty interval of s.
#pragma once

#include <Eigen/Geometry>
#include <array>

#include "common/camera/camera_calibration.h"

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
  std::array<Eigen::Vector4d, 6> planes_world_;  // (n, d): inside when n . x + d >= 0
  Eigen::AlignedBox3d bounds_world_;
};

}  // namespace lineloc::db
