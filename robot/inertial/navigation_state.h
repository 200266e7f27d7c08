// The strapdown navigation state and its 15-dimensional error state.
//
// Nominal state: position and velocity of the body in the world (site) frame,
// attitude R_world_body, gyro and accelerometer biases (Solà, "Quaternion
// kinematics for the error-state Kalman filter", 2017, §5.3.1). Error state
// dx = [dp, dv, dtheta, dbg, dba] with p = p_est + dp, R = Exp(dtheta) R_est
// (dtheta in the world frame, §7: global error), the same left perturbation as
// the pose covariance of common/geometry/pose.h.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

#include "common/geometry/pose.h"

namespace lineloc {

inline constexpr int kErrorStateSize = 15;
using ErrorVector = Eigen::Matrix<double, kErrorStateSize, 1>;
using ErrorCovariance = Eigen::Matrix<double, kErrorStateSize, kErrorStateSize>;

// Offsets of the 3-vectors inside the error state.
enum ErrorBlock : int {
  kPosition = 0,
  kVelocity = 3,
  kAttitude = 6,
  kGyroBias = 9,
  kAccelBias = 12,
};

struct NavigationState {
  int64_t stamp_ns = 0;
  Eigen::Vector3d p_world_body = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_world_body = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_world_body = Eigen::Quaterniond::Identity();
  Eigen::Vector3d gyro_bias_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias_mps2 = Eigen::Vector3d::Zero();
};

// The covariance of the body's pose error [dp; dtheta] inside `covariance`.
Matrix6d poseBlock(const ErrorCovariance& covariance);
// Writes `pose` over that block, leaving the rest of `covariance` as it is.
void setPoseBlock(const Matrix6d& pose, ErrorCovariance& covariance);

// Applies an error-state correction: p += dp, v += dv, R = Exp(dtheta) R, b += db.
void injectError(const ErrorVector& dx, NavigationState& state);

// The error that takes `estimate` to `truth` (the inverse of injectError):
// dtheta = Log(R_truth R_estimate^T).
ErrorVector errorBetween(const NavigationState& truth, const NavigationState& estimate);

// SO(3) exponential and logarithm on rotation vectors (radians).
Eigen::Quaterniond expSO3(const Eigen::Vector3d& rotation_vector);
Eigen::Vector3d logSO3(const Eigen::Quaterniond& rotation);

}  // namespace lineloc
