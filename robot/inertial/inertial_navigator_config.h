// The settings of the inertial navigator (inertial_navigator.h) and of the
// parts it is made of: the IMU's noise, range and mounting, the other sensors'
// mounting and noise, the start-up, the restarts and the model of the vision
// fixes' correlated error. Each setting's header says what it does.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>

#include "robot/inertial/imu_sample.h"
#include "robot/inertial/navigator_measurements.h"
#include "robot/inertial/stillness_detector.h"

namespace lineloc {

struct InertialNavigatorConfig {
  ImuNoiseDensities imu_noise;
  double gravity_mps2 = 9.80665;
  // Samples beyond the IMU's range are saturated, hence wrong (ADIS16448: ±1000 deg/s, ±18 g).
  double gyro_range_radps = 17.45;
  double accel_range_mps2 = 176.5;
  int64_t imu_gap_ns = 20'000'000;
  // Rotation from the IMU's frame to the body frame, applied to every sample
  // (the lever arm's centripetal terms are neglected: small on a ground robot).
  Eigen::Matrix3d R_body_imu = Eigen::Matrix3d::Identity();
  // Camera mounted looking forward: camera z = body x, camera x = -body y, camera y = -body z.
  Eigen::Isometry3d T_body_camera = defaultBodyCamera();
  Eigen::Vector3d p_body_gps_antenna = Eigen::Vector3d::Zero();
  // Long enough for a fix found by the backbone's search from a DGPS start,
  // which answers its frame a second or two late (measurement_history.h).
  int64_t history_ns = 3'000'000'000;
  double gate_probability = 0.999;

  // Still: per-axis standard deviations within twice the white noise of one
  // sample (ADIS16448 at 200 Hz: 0.0024 rad/s, 0.028 m/s^2). Looser thresholds
  // let a robot that is pulling away at a few cm/s pass for standing.
  StillnessThresholds alignment{2'000'000'000, 0.005, 0.056};
  StillnessThresholds zero_velocity{500'000'000, 0.005, 0.056};
  double zero_velocity_max_speed_mps = 0.1;
  // The fastest the robot drives: the velocity sigma of a start whose
  // stillness only the IMU saw (startup_alignment.h).
  double max_ground_speed_mps = 3.0;
  // Covers the speed a trailing window misses when the robot pulls away (a few
  // cm/s).
  double zero_velocity_sigma_mps = 0.05;
  int64_t zero_velocity_interval_ns = 100'000'000;

  double gps_horizontal_sigma_m = 5.0;
  double gps_vertical_sigma_m = 10.0;
  // Per horizontal axis, of one DGPS velocity (Doppler: 0.05 m/s on a current
  // single-frequency receiver's data sheet, doubled for multipath in a street).
  double gps_velocity_sigma_mps = 0.1;
  // A compass reading's error: white noise from reading to reading, and an
  // error all readings share (calibration, mounting, the magnetic field of
  // the street), which no number of readings averages away. Each reading
  // bounds the yaw at sigma_c = hypot(white, shared) rather than shrinking it
  // (navigation_filter.h), and a start from the compass has that yaw sigma.
  double compass_sigma_rad = 2.0 * M_PI / 180.0;
  double compass_bias_sigma_rad = 2.0 * M_PI / 180.0;
  double magnetic_declination_rad = 0.0;  // magnetic north's bearing from true north, east positive
  double grid_bearing_of_true_north_rad = 0.0;  // SiteProjection::gridBearingOfTrueNorth_rad
  double gyro_turn_on_bias_sigma_radps = 0.0035;
  double accel_turn_on_bias_sigma_mps2 = 0.05;

  // Compass readings gated without a break for this long, agreeing on one
  // offset from the filter's heading, with no vision fix applied, restart the
  // heading from them (0: never). Longer than a disturbance lasts (steel, a
  // passing car: seconds); the simulator's last 2-6 s.
  int64_t compass_gated_restart_after_ns = 8'000'000'000;

  // Vision fixes gated without a break for this long, moving together, restart
  // the filter from the newest (0: never).
  int64_t vision_gated_restart_after_ns = 1'000'000'000;

  // Correlation lengths of the vision fixes' error in travel and in turn
  // (L_p, L_theta, correlated_fix_model.h); 0: independent fixes.
  double vision_error_correlation_m = 0.01;
  double vision_error_correlation_rad = 0.1 * M_PI / 180.0;
  // Fraction f of a fix's covariance its error shares with the fixes around it
  // over metres of travel, below which the reported covariance does not fall
  // (correlated_fix_model.h); 0: independent fixes.
  double shared_fix_error_fraction = 0.5;
  // Correlation length L_s of that shared error in travel, over which the
  // filter forgets it (correlated_fix_model.h); 0: never.
  double shared_fix_error_length_m = 0.0;

  int64_t tracking_timeout_ns = 1'000'000'000;
  double lost_position_sigma_m = 10.0;

  static Eigen::Isometry3d defaultBodyCamera();
};

// Throws std::invalid_argument naming the first invalid setting.
void validate(const InertialNavigatorConfig& config);

// sigma_c = hypot(compass_sigma_rad, compass_bias_sigma_rad): the yaw sigma
// of one compass reading, and of a start from the compass.
double compassYawSigma_rad(const InertialNavigatorConfig& config);

// A DGPS fix's standard deviations along site x, y and z (m): the fix's own
// where the receiver reported them (GpsFix), else gps_horizontal_sigma_m and
// gps_vertical_sigma_m.
Eigen::Vector3d gpsFixSigmas(const GpsFix& fix, const InertialNavigatorConfig& config);

}  // namespace lineloc
