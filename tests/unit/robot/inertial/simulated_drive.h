// Test helpers: a simulated drive turned into the navigator's inputs and truth.
#pragma once

#include <random>
#include <vector>

#include "common/geometry/pose.h"
#include "robot/inertial/imu_sample.h"
#include "robot/inertial/inertial_navigator.h"
#include "robot/inertial/navigation_state.h"
#include "sim/sensors/sensor_synthesis.h"

namespace lineloc::testing {

inline ImuSample toImuSample(const sim::SimImuSample& s) {
  return {s.stamp_ns, s.gyro_radps, s.accel_mps2};
}

inline NavigationState truthState(const sim::GroundTruthTrajectory& trajectory, int64_t stamp_ns,
                                  const sim::SimImuSample* biases = nullptr) {
  const sim::TruthSample truth = trajectory.at(stamp_ns);
  NavigationState state;
  state.stamp_ns = stamp_ns;
  state.p_world_body = truth.p_world_body;
  state.v_world_body = truth.v_world_body;
  state.q_world_body = truth.q_world_body;
  if (biases != nullptr) {
    state.gyro_bias_radps = biases->true_gyro_bias_radps;
    state.accel_bias_mps2 = biases->true_accel_bias_mps2;
  }
  return state;
}

// A vision fix: the true camera pose perturbed by N(0, diag(sp^2, sr^2)) in
// the left-perturbation convention of common/geometry/pose.h.
inline PoseWithCovariance noisyCameraFix(const sim::GroundTruthTrajectory& trajectory,
                                         int64_t stamp_ns, const Eigen::Isometry3d& T_body_camera,
                                         double position_sigma_m, double rotation_sigma_rad,
                                         std::mt19937_64& random) {
  const sim::TruthSample truth = trajectory.at(stamp_ns);
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
  T_world_body.linear() = truth.q_world_body.toRotationMatrix();
  T_world_body.translation() = truth.p_world_body;
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Vector3d dp(normal(random), normal(random), normal(random));
  const Eigen::Vector3d dtheta(normal(random), normal(random), normal(random));
  PoseWithCovariance fix;
  fix.pose = T_world_body * T_body_camera;
  fix.pose.translation() += position_sigma_m * dp;
  fix.pose.linear() = (expSO3(rotation_sigma_rad * dtheta) * Eigen::Quaterniond(fix.pose.linear()))
                          .toRotationMatrix();
  fix.covariance = diagonalPoseCovariance(position_sigma_m, rotation_sigma_rad);
  return fix;
}

inline ImuNoiseDensities densitiesOf(const sim::ImuModel& model) {
  ImuNoiseDensities densities;
  densities.gyro_noise_radps_per_sqrt_hz = model.gyro_noise_radps_per_sqrt_hz;
  densities.accel_noise_mps2_per_sqrt_hz = model.accel_noise_mps2_per_sqrt_hz;
  densities.gyro_bias_random_walk_radps2_per_sqrt_hz =
      model.gyro_bias_random_walk_radps2_per_sqrt_hz;
  densities.accel_bias_random_walk_mps3_per_sqrt_hz = model.accel_bias_random_walk_mps3_per_sqrt_hz;
  return densities;
}

// The simulator's DGPS receiver, never out.
inline sim::GpsModel dgpsWithoutOutages() {
  sim::GpsModel model;
  model.outage_probability = 0.0;
  return model;
}

}  // namespace lineloc::testing
