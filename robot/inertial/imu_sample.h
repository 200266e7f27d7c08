// One IMU measurement in the body frame (x forward, y left, z up): angular
// rate and specific force (acceleration minus gravity), stamped with the time
// it was measured.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace lineloc {

struct ImuSample {
  int64_t stamp_ns = 0;
  Eigen::Vector3d gyro_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();
};

// Continuous-time noise densities of a MEMS IMU, as a datasheet or a Kalibr
// IMU file gives them: white noise on the rates and random walk of the biases.
struct ImuNoiseDensities {
  double gyro_noise_radps_per_sqrt_hz = 1.6968e-4;
  double accel_noise_mps2_per_sqrt_hz = 2.0e-3;
  double gyro_bias_random_walk_radps2_per_sqrt_hz = 1.9393e-5;
  double accel_bias_random_walk_mps3_per_sqrt_hz = 3.0e-3;
};

// Linear interpolation of rates and specific force at `stamp_ns` between a and b.
ImuSample interpolateImu(const ImuSample& a, const ImuSample& b, int64_t stamp_ns);

}  // namespace lineloc
