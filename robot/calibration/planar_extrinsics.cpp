#include "robot/calibration/planar_extrinsics.h"

#include <Eigen/LU>

#include "common/pose/nearest_rotation.h"

namespace lineloc {

Eigen::Isometry3d planePoseFromHomography(const Eigen::Matrix3d& K, const Eigen::Matrix3d& H) {
  const Eigen::Matrix3d K_inverse_H = K.inverse() * H;
  double lambda = 1.0 / K_inverse_H.col(0).norm();
  if (K_inverse_H(2, 2) * lambda < 0.0) {
    lambda = -lambda;
  }
  const Eigen::Vector3d r1 = lambda * K_inverse_H.col(0);
  const Eigen::Vector3d r2 = lambda * K_inverse_H.col(1);
  Eigen::Matrix3d Q;
  Q << r1, r2, r1.cross(r2);
  Eigen::Isometry3d T_camera_model = Eigen::Isometry3d::Identity();
  T_camera_model.linear() = nearestRotation(Q);
  T_camera_model.translation() = lambda * K_inverse_H.col(2);
  return T_camera_model;
}

}  // namespace lineloc
