// Synthetic IMU, DGPS and compass measurements along a ground-truth
// trajectory, deterministic per seed, and the files a real robot's drivers
// would write: EuRoC/ASL imu0/data.csv, NMEA 0183 (GGA + RMC), a compass CSV.
//
// IMU model (Kalibr/EuRoC convention): measured = true + bias + white noise,
// the discrete white noise having sigma = density / sqrt(dt) and the bias a
// random walk b_k+1 = b_k + rw sqrt(dt) n, started from a turn-on bias drawn
// per axis. Defaults: the Analog Devices ADIS16448 as configured for the EuRoC
// MAV dataset (imu0/sensor.yaml: gyro 1.6968e-4 rad/s/sqrt(Hz), accel 2.0e-3
// m/s^2/sqrt(Hz), bias walks 1.9393e-5 rad/s^2/sqrt(Hz) and 3.0e-3
// m/s^3/sqrt(Hz)), 200 Hz; turn-on biases of 0.2 deg/s and 5 mg.
//
// DGPS: per-axis first-order Gauss-Markov errors (sigma 4 m horizontal,
// correlation 60 s: fixes 5-10 m off that wander slowly), white noise on top,
// 1 Hz, outages that start with a given probability per fix. The correlated
// error starts in the process's stationary distribution, N(0, sigma^2) per
// axis, or, with initial_horizontal_error_m = m > 0, horizontally at
//   e_0 = m (n_x, n_y) / |(n_x, n_y)|,
// (n_x, n_y) the standard normal pair the stationary start would have scaled
// by sigma: a direction uniform on the circle, drawn from the seed, and every
// later draw the same as without it. From there the process runs as always,
//   e_k+1 = a e_k + sigma sqrt(1 - a^2) n_k,  a = exp(-dt / correlation_time_s),
// so E[e_k] = a^k e_0: the start's offset decays with the correlation time
// (10 m -> 3.7 m after 60 s) while the stationary spread grows back,
// Var[e_k] = sigma^2 (1 - a^2k) per axis. A 10 m start at sigma 4 m is a
// state the stationary process is in 4.4 % of the time (P(|e| > m) =
// exp(-m^2 / 2 sigma^2)): multipath in a street canyon, a stale correction.
// Compass: 10 Hz magnetic heading with white noise, plus disturbances (steel,
// cars, power lines) that add a fixed 10-40 deg offset for a few seconds, plus
// a constant bias (bias_rad, added to every reading: a compass calibrated
// elsewhere or mounted turned), so a clean reading's mean is the true magnetic
// heading + bias_rad.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/geodesy/site_projection.h"
#include "sim/sensors/ground_truth_trajectory.h"

namespace lineloc::sim {

struct ImuModel {
  double rate_hz = 200.0;
  double gyro_noise_radps_per_sqrt_hz = 1.6968e-4;
  double accel_noise_mps2_per_sqrt_hz = 2.0e-3;
  double gyro_bias_random_walk_radps2_per_sqrt_hz = 1.9393e-5;
  double accel_bias_random_walk_mps3_per_sqrt_hz = 3.0e-3;
  double gyro_turn_on_bias_sigma_radps = 0.0035;
  double accel_turn_on_bias_sigma_mps2 = 0.05;
  bool noise = true;  // false: exact rates and forces, zero biases
};

struct SimImuSample {
  int64_t stamp_ns = 0;
  Eigen::Vector3d gyro_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d true_gyro_bias_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d true_accel_bias_mps2 = Eigen::Vector3d::Zero();
};

std::vector<SimImuSample> synthesiseImu(const TruthTrajectory& trajectory, const ImuModel& model,
                                        uint64_t seed);

struct GpsModel {
  double rate_hz = 1.0;
  double correlated_horizontal_sigma_m = 4.0;
  double correlated_vertical_sigma_m = 6.0;
  double correlation_time_s = 60.0;
  double white_sigma_m = 0.3;
  // Horizontal velocity from the carrier's Doppler shift, white per axis (a
  // current single-frequency receiver's specification: 0.05 m/s).
  double velocity_sigma_mps = 0.05;
  double outage_probability = 0.01;  // per fix, that an outage starts
  // Magnitude of the correlated horizontal error at the first fix (m); 0: drawn
  // from the stationary distribution (see the header comment).
  double initial_horizontal_error_m = 0.0;
  double min_outage_s = 5.0;
  double max_outage_s = 30.0;
  Eigen::Vector3d p_body_antenna = Eigen::Vector3d::Zero();
};

struct SimGpsFix {
  int64_t stamp_ns = 0;
  bool valid = false;  // false during an outage
  Eigen::Vector3d p_world_antenna = Eigen::Vector3d::Zero();
  Eigen::Vector3d true_p_world_antenna = Eigen::Vector3d::Zero();
  // Horizontal: site x (east), y (north).
  Eigen::Vector2d v_world_antenna_mps = Eigen::Vector2d::Zero();
  Eigen::Vector2d true_v_world_antenna_mps = Eigen::Vector2d::Zero();
};

// Throws std::invalid_argument for a negative or non-finite initial_horizontal_error_m.
std::vector<SimGpsFix> synthesiseGps(const TruthTrajectory& trajectory, const GpsModel& model,
                                     uint64_t seed);

// GGA then RMC of one fix (no position and quality 0 / status V when invalid);
// RMC's speed and course are the velocity's, the course a true bearing.
std::vector<std::string> formatNmeaEpoch(const SimGpsFix& fix, const SiteProjection& projection);

struct CompassModel {
  double rate_hz = 10.0;
  double sigma_rad = 2.0 * M_PI / 180.0;
  double magnetic_declination_rad = 0.0;
  double disturbance_rate_hz = 1.0 / 60.0;
  double min_disturbance_rad = 0.17;
  double max_disturbance_rad = 0.7;
  double min_disturbance_s = 2.0;
  double max_disturbance_s = 6.0;
  // Added to every reading (rad); positive: the reading is clockwise of the truth.
  double bias_rad = 0.0;
};

struct SimCompassReading {
  int64_t stamp_ns = 0;
  double magnetic_heading_rad = 0.0;  // clockwise from magnetic north, [0, 2 pi)
  bool disturbed = false;
};

// `grid_bearing_of_true_north_rad` from SiteProjection: magnetic heading =
// pi/2 - yaw - grid bearing of true north - declination + bias + noise
// (+ a disturbance's offset while one lasts), wrapped to [0, 2 pi).
std::vector<SimCompassReading> synthesiseCompass(const TruthTrajectory& trajectory,
                                                 const CompassModel& model,
                                                 double grid_bearing_of_true_north_rad,
                                                 uint64_t seed);

// Writers; each throws std::runtime_error naming the path it cannot write.
void writeEurocImuCsv(const std::string& path, const std::vector<SimImuSample>& samples);
void writeCompassCsv(const std::string& path, const std::vector<SimCompassReading>& readings);
void writeNmeaFile(const std::string& path, const std::vector<SimGpsFix>& fixes,
                   const SiteProjection& projection);

}  // namespace lineloc::sim
