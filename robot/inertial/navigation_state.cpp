#include "robot/inertial/navigation_state.h"

#include <cmath>

namespace lineloc {
namespace {

// Below this angle the Taylor series of sin(x/2)/x is exact in double.
constexpr double kSmallAngle_rad = 1e-8;

}  // namespace

Eigen::Quaterniond expSO3(const Eigen::Vector3d& rotation_vector) {
  const double angle = rotation_vector.norm();
  // q = [cos(angle/2), sin(angle/2) axis]; sin(angle/2)/angle -> 1/2 - angle^2/48.
  const double half_sinc =
      angle < kSmallAngle_rad ? 0.5 - angle * angle / 48.0 : std::sin(0.5 * angle) / angle;
  const Eigen::Vector3d xyz = half_sinc * rotation_vector;
  return Eigen::Quaterniond(std::cos(0.5 * angle), xyz.x(), xyz.y(), xyz.z());
}

Eigen::Vector3d logSO3(const Eigen::Quaterniond& rotation) {
  // The shortest rotation: w >= 0; angle = 2 atan2(|xyz|, w).
  const Eigen::Quaterniond q =
      rotation.w() < 0.0 ? Eigen::Quaterniond(-rotation.coeffs()) : rotation;
  const double sin_half = q.vec().norm();
  if (sin_half < kSmallAngle_rad) {
    return 2.0 * q.vec() / q.w();
  }
  return (2.0 * std::atan2(sin_half, q.w()) / sin_half) * q.vec();
}

Matrix6d poseBlock(const ErrorCovariance& covariance) {
  Matrix6d pose;
  pose << covariance.block<3, 3>(kPosition, kPosition),
      covariance.block<3, 3>(kPosition, kAttitude), covariance.block<3, 3>(kAttitude, kPosition),
      covariance.block<3, 3>(kAttitude, kAttitude);
  return pose;
}

void setPoseBlock(const Matrix6d& pose, ErrorCovariance& covariance) {
  covariance.block<3, 3>(kPosition, kPosition) = pose.topLeftCorner<3, 3>();
  covariance.block<3, 3>(kPosition, kAttitude) = pose.topRightCorner<3, 3>();
  covariance.block<3, 3>(kAttitude, kPosition) = pose.bottomLeftCorner<3, 3>();
  covariance.block<3, 3>(kAttitude, kAttitude) = pose.bottomRightCorner<3, 3>();
}

void injectError(const ErrorVector& dx, NavigationState& state) {
  state.p_world_body += dx.segment<3>(kPosition);
  state.v_world_body += dx.segment<3>(kVelocity);
  state.q_world_body = (expSO3(dx.segment<3>(kAttitude)) * state.q_world_body).normalized();
  state.gyro_bias_radps += dx.segment<3>(kGyroBias);
  state.accel_bias_mps2 += dx.segment<3>(kAccelBias);
}

ErrorVector errorBetween(const NavigationState& truth, const NavigationState& estimate) {
  ErrorVector dx;
  dx.segment<3>(kPosition) = truth.p_world_body - estimate.p_world_body;
  dx.segment<3>(kVelocity) = truth.v_world_body - estimate.v_world_body;
  dx.segment<3>(kAttitude) = logSO3(truth.q_world_body * estimate.q_world_body.conjugate());
  dx.segment<3>(kGyroBias) = truth.gyro_bias_radps - estimate.gyro_bias_radps;
  dx.segment<3>(kAccelBias) = truth.accel_bias_mps2 - estimate.accel_bias_mps2;
  return dx;
}

}  // namespace lineloc
