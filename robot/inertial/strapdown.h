// Strapdown mechanisation and error-state propagation between two IMU samples
// (Solà, "Quaternion kinematics for the error-state Kalman filter", 2017:
// nominal kinematics eq. 260, global-error dynamics §7.3, transition matrix
// §5.3.3 truncated at second order, eq. 355).
//
// Nominal step over dt = t_b - t_a with trapezoidal rates and forces:
//   R_b = R_a Exp((w_a + w_b)/2 - b_g) dt)
//   a_i = R_i (f_i - b_a) + g,  v_b = v_a + (a_a + a_b)/2 dt,  p_b = p_a + (v_a + v_b)/2 dt
// Error dynamics with the world-frame attitude error (no Earth rate: the site
// frame is treated as inertial, fine for MEMS gyros and a city-sized site):
//   dp' = dv,  dv' = -[R f]x dtheta - R dba - R n_a,  dtheta' = -R dbg - R n_g,
//   dbg' = n_bg,  dba' = n_ba.
// Phi = I + F dt + F^2 dt^2 / 2 is applied block-sparsely: 7 non-zero 3x3
// blocks instead of a dense 15x15 product.
#pragma once

#include "robot/inertial/imu_sample.h"
#include "robot/inertial/navigation_state.h"

namespace lineloc {

// The non-identity blocks of the error-state transition Phi for one step.
struct ErrorTransition {
  double dt_s = 0.0;
  Eigen::Matrix3d p_theta;   // -[f]x dt^2/2
  Eigen::Matrix3d p_ba;      // -R dt^2/2
  Eigen::Matrix3d v_theta;   // -[f]x dt
  Eigen::Matrix3d v_bg;      // [f]x R dt^2/2
  Eigen::Matrix3d v_ba;      // -R dt
  Eigen::Matrix3d theta_bg;  // -R dt

  ErrorCovariance toMatrix() const;
  // Phi * M, touching only the rows of position, velocity and attitude.
  ErrorCovariance applyLeft(const ErrorCovariance& m) const;
};

// Discrete process noise of one step for the densities, Q = integral of
// Phi G Qc G^T Phi^T to the first order in each block (Q_pp = s_a^2 dt^3/3,
// Q_pv = s_a^2 dt^2/2, Q_vv = s_a^2 dt, Q_thth = s_g^2 dt, Q_b = s_b^2 dt).
class ProcessNoise {
 public:
  explicit ProcessNoise(const ImuNoiseDensities& densities);
  void addTo(double dt_s, ErrorCovariance& covariance) const;

 private:
  double accel_psd_;
  double gyro_psd_;
  double gyro_bias_psd_;
  double accel_bias_psd_;
};

class Strapdown {
 public:
  Strapdown(const ImuNoiseDensities& densities, const Eigen::Vector3d& gravity_world_mps2);

  // Moves `state` from sample a to sample b (state.stamp_ns must be a's stamp)
  // and returns the transition of the error state over that step.
  ErrorTransition propagate(const ImuSample& a, const ImuSample& b, NavigationState& state) const;

  // Propagates state and covariance together: P = Phi P Phi^T + Q.
  void propagate(const ImuSample& a, const ImuSample& b, NavigationState& state,
                 ErrorCovariance& covariance) const;

  const Eigen::Vector3d& gravity() const { return gravity_world_mps2_; }

 private:
  ProcessNoise process_noise_;
  Eigen::Vector3d gravity_world_mps2_;
};

}  // namespace lineloc
