// The pose of the model plane from its homography and K, Zhang (ICCV 1999)
// §3.1 and Appendix C:
//
//   lambda = 1 / ||K^-1 h1||,  r1 = lambda K^-1 h1,  r2 = lambda K^-1 h2,
//   r3 = r1 x r2,              t = lambda K^-1 h3,
//
// with the sign of lambda chosen so that the plane lies in front of the camera
// (t_z > 0), and Q = [r1 r2 r3] replaced by the nearest rotation in Frobenius
// norm (common/pose/nearest_rotation.h).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lineloc {

// T_camera_model: maps model points (X, Y, 0) to the camera frame.
Eigen::Isometry3d planePoseFromHomography(const Eigen::Matrix3d& K, const Eigen::Matrix3d& H);

}  // namespace lineloc
