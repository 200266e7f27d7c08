// Measurement models of the navigation filter, linearised at the current
// estimate in the error state of navigation_state.h (dtheta in the world frame).
//
//  - Camera pose fix T_world_camera (6): with T_world_camera = T_world_body
//    T_body_camera, p_c = p + R t_bc and R_c = R R_bc, so
//    dp_c = dp - [R t_bc]x dtheta and dtheta_c = dtheta; the residual is
//    [p_meas - p_c; Log(R_meas R_c^T)], matching the pose covariance convention.
//  - Antenna position (3): p_a = p + R l, dp_a = dp - [R l]x dtheta.
//  - Yaw (1), the heading of the body x axis u = R e_x in the world xy plane:
//    psi = atan2(u_y, u_x); du = dtheta x u gives
//    dpsi = (-u_x u_z dtheta_x - u_y u_z dtheta_y + (u_x^2 + u_y^2) dtheta_z) / (u_x^2 + u_y^2).
//  - Antenna velocity over ground (2, x and y): v_a = v + R (omega x l), with
//    omega = w_meas - b_g the body's rate; dv_a = dv - [R (omega x l)]x dtheta
//    + R [l]x db_g.
//  - Zero velocity (3): v = 0.
#pragma once

#include <optional>

#include "common/geometry/pose.h"
#include "robot/inertial/error_state_update.h"

namespace lineloc {

LinearisedMeasurement<6> linearisePoseFix(const NavigationState& state,
                                          const PoseWithCovariance& T_world_camera,
                                          const Eigen::Isometry3d& T_body_camera);

LinearisedMeasurement<3> lineariseAntennaPosition(const NavigationState& state,
                                                  const Eigen::Vector3d& p_world_antenna,
                                                  const Eigen::Matrix3d& covariance,
                                                  const Eigen::Vector3d& p_body_antenna);

// `gyro_radps`: the gyros' reading at the measurement's time, biases not removed.
LinearisedMeasurement<2> lineariseAntennaVelocity(const NavigationState& state,
                                                  const Eigen::Vector3d& gyro_radps,
                                                  const Eigen::Vector2d& v_world_antenna_mps,
                                                  double sigma_mps,
                                                  const Eigen::Vector3d& p_body_antenna);

// nullopt when the body x axis is within ~18 deg of vertical (yaw undefined).
std::optional<LinearisedMeasurement<1>> lineariseYaw(const NavigationState& state, double yaw_rad,
                                                     double sigma_rad);

LinearisedMeasurement<3> lineariseZeroVelocity(const NavigationState& state, double sigma_mps);

// Yaw of the body x axis, anticlockwise from world x (east), in (-pi, pi].
double yawOf(const Eigen::Quaterniond& q_world_body);

// Wraps an angle to (-pi, pi].
double wrapAngle(double angle_rad);

// T_world_camera and its covariance from the navigation state and covariance.
PoseWithCovariance cameraPoseOf(const NavigationState& state, const ErrorCovariance& covariance,
                                const Eigen::Isometry3d& T_body_camera);

// The covariance of the body's pose error [dp; dtheta] from that of the
// camera's pose T_world_camera: the camera's pose moved by the exact camera ->
// body transform, the inverse of cameraPoseOf's lever-arm Jacobian.
Matrix6d bodyPoseCovarianceOf(const Eigen::Isometry3d& T_world_camera,
                              const Matrix6d& camera_covariance,
                              const Eigen::Isometry3d& T_body_camera);

}  // namespace lineloc
