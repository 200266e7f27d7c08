// How far an estimated pose is from the truth in its own reported
// uncertainty, for tests that check "no precise wrong pose" (paper §3.2).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "common/geometry/pose.h"

namespace lineloc::test {

// chi^2_6(0.9973): the 6-D equivalent of three standard deviations.
inline constexpr double kChi2Six9973 = 20.06;

// chi^2_6(0.999): a consistent estimate exceeds it once in a thousand trials.
inline constexpr double kChi2Six999 = 22.46;

// e = [dp; dtheta] taking `estimate` to `truth` in the covariance convention of
// common/geometry/pose.h.
inline Eigen::Matrix<double, 6, 1> poseError(const Eigen::Isometry3d& estimate,
                                             const Eigen::Isometry3d& truth) {
  Eigen::Matrix<double, 6, 1> error;
  error.head<3>() = truth.translation() - estimate.translation();
  const Eigen::AngleAxisd rotation(truth.linear() * estimate.linear().transpose());
  error.tail<3>() = rotation.angle() * rotation.axis();
  return error;
}

// e^T Sigma^-1 e: the estimate's error in its own reported uncertainty.
inline double normalizedErrorSquared(const PoseWithCovariance& estimate,
                                     const Eigen::Isometry3d& truth) {
  const Eigen::Matrix<double, 6, 1> error = poseError(estimate.pose, truth);
  return error.dot(estimate.covariance.ldlt().solve(error));
}

}  // namespace lineloc::test
