#include "robot/inertial/measurement_models.h"

#include <cmath>

#include "common/geometry/pose.h"

namespace lineloc {
namespace {

// Yaw is measured only while the body x axis is at least 0.3 (~18 deg of
// elevation from vertical) out of the vertical: squared horizontal length 0.1.
constexpr double kMinHorizontalNormSquared = 0.1;

// d(p + R offset) / d(dx) for a point at `offset` in the body frame.
Eigen::Matrix<double, 3, kErrorStateSize> offsetPointJacobian(const Eigen::Matrix3d& R,
                                                              const Eigen::Vector3d& offset) {
  Eigen::Matrix<double, 3, kErrorStateSize> H = Eigen::Matrix<double, 3, kErrorStateSize>::Zero();
  H.block<3, 3>(0, kPosition).setIdentity();
  H.block<3, 3>(0, kAttitude) = -skew(R * offset);
  return H;
}

}  // namespace

double wrapAngle(double angle_rad) {
  const double wrapped = std::remainder(angle_rad, 2.0 * M_PI);
  return wrapped <= -M_PI ? wrapped + 2.0 * M_PI : wrapped;
}

double yawOf(const Eigen::Quaterniond& q_world_body) {
  const Eigen::Vector3d u = q_world_body * Eigen::Vector3d::UnitX();
  return std::atan2(u.y(), u.x());
}

LinearisedMeasurement<6> linearisePoseFix(const NavigationState& state,
                                          const PoseWithCovariance& T_world_camera,
                                          const Eigen::Isometry3d& T_body_camera) {
  const Eigen::Matrix3d R = state.q_world_body.toRotationMatrix();
  const Eigen::Vector3d p_camera = state.p_world_body + R * T_body_camera.translation();
  const Eigen::Quaterniond q_camera(R * T_body_camera.linear());
  const Eigen::Quaterniond q_measured(T_world_camera.pose.linear());
  LinearisedMeasurement<6> z;
  z.residual.head<3>() = T_world_camera.pose.translation() - p_camera;
  z.residual.tail<3>() = logSO3(q_measured * q_camera.conjugate());
  z.jacobian.topRows<3>() = offsetPointJacobian(R, T_body_camera.translation());
  z.jacobian.block<3, 3>(3, kAttitude).setIdentity();
  z.noise = T_world_camera.covariance;
  return z;
}

LinearisedMeasurement<3> lineariseAntennaPosition(const NavigationState& state,
                                                  const Eigen::Vector3d& p_world_antenna,
                                                  const Eigen::Matrix3d& covariance,
                                                  const Eigen::Vector3d& p_body_antenna) {
  const Eigen::Matrix3d R = state.q_world_body.toRotationMatrix();
  LinearisedMeasurement<3> z;
  z.residual = p_world_antenna - (state.p_world_body + R * p_body_antenna);
  z.jacobian = offsetPointJacobian(R, p_body_antenna);
  z.noise = covariance;
  return z;
}

LinearisedMeasurement<2> lineariseAntennaVelocity(const NavigationState& state,
                                                  const Eigen::Vector3d& gyro_radps,
                                                  const Eigen::Vector2d& v_world_antenna_mps,
                                                  double sigma_mps,
                                                  const Eigen::Vector3d& p_body_antenna) {
  const Eigen::Matrix3d R = state.q_world_body.toRotationMatrix();
  const Eigen::Vector3d lever_velocity =
      R * (gyro_radps - state.gyro_bias_radps).cross(p_body_antenna);
  LinearisedMeasurement<2> z;
  z.residual = v_world_antenna_mps - (state.v_world_body + lever_velocity).head<2>();
  z.jacobian.block<2, 3>(0, kVelocity).setIdentity();
  z.jacobian.block<2, 3>(0, kAttitude) = -skew(lever_velocity).topRows<2>();
  z.jacobian.block<2, 3>(0, kGyroBias) = (R * skew(p_body_antenna)).topRows<2>();
  z.noise = Eigen::Matrix2d::Identity() * sigma_mps * sigma_mps;
  return z;
}

std::optional<LinearisedMeasurement<1>> lineariseYaw(const NavigationState& state, double yaw_rad,
                                                     double sigma_rad) {
  const Eigen::Vector3d u = state.q_world_body * Eigen::Vector3d::UnitX();
  const double horizontal = u.x() * u.x() + u.y() * u.y();
  if (horizontal < kMinHorizontalNormSquared) {
    return std::nullopt;
  }
  LinearisedMeasurement<1> z;
  z.residual(0) = wrapAngle(yaw_rad - std::atan2(u.y(), u.x()));
  z.jacobian(0, kAttitude + 0) = -u.x() * u.z() / horizontal;
  z.jacobian(0, kAttitude + 1) = -u.y() * u.z() / horizontal;
  z.jacobian(0, kAttitude + 2) = 1.0;
  z.noise(0, 0) = sigma_rad * sigma_rad;
  return z;
}

LinearisedMeasurement<3> lineariseZeroVelocity(const NavigationState& state, double sigma_mps) {
  LinearisedMeasurement<3> z;
  z.residual = -state.v_world_body;
  z.jacobian.block<3, 3>(0, kVelocity).setIdentity();
  z.noise = Eigen::Matrix3d::Identity() * sigma_mps * sigma_mps;
  return z;
}

PoseWithCovariance cameraPoseOf(const NavigationState& state, const ErrorCovariance& covariance,
                                const Eigen::Isometry3d& T_body_camera) {
  const Eigen::Matrix3d R = state.q_world_body.toRotationMatrix();
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
  T_world_body.linear() = R;
  T_world_body.translation() = state.p_world_body;
  Eigen::Matrix<double, 6, kErrorStateSize> J = Eigen::Matrix<double, 6, kErrorStateSize>::Zero();
  J.topRows<3>() = offsetPointJacobian(R, T_body_camera.translation());
  J.block<3, 3>(3, kAttitude).setIdentity();
  PoseWithCovariance pose;
  pose.pose = T_world_body * T_body_camera;
  pose.covariance = J * covariance * J.transpose();
  return pose;
}

Matrix6d bodyPoseCovarianceOf(const Eigen::Isometry3d& T_world_camera,
                              const Matrix6d& camera_covariance,
                              const Eigen::Isometry3d& T_body_camera) {
  return composeExactMotion({T_world_camera, camera_covariance}, T_body_camera.inverse())
      .covariance;
}

}  // namespace lineloc
