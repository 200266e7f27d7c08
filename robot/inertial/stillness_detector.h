// Detects standing still from the IMU alone and, over a long enough still
// window, gives the static alignment (Groves, "Principles of GNSS, Inertial,
// and Multisensor Integrated Navigation Systems", 2nd ed., 2013, §5.6.2
// levelling and gyrocompass-free bias calibration): with f the mean specific
// force in the body frame (gravity reaction, pointing up),
//   roll = atan2(f_y, f_z),  pitch = atan2(-f_x, sqrt(f_y^2 + f_z^2)),
// and the gyro bias is the mean angular rate.
//
// Still means every axis's standard deviation over the window is below its
// threshold. A ground robot cruising on a perfectly smooth road is as quiet as
// a standing one, so the navigator also requires a small estimated speed.
#pragma once

#include <deque>
#include <optional>

#include "robot/inertial/imu_sample.h"

namespace lineloc {

struct StillnessThresholds {
  int64_t window_ns = 500'000'000;
  double gyro_std_radps = 0.01;
  double accel_std_mps2 = 0.1;
};

struct StaticAlignment {
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  Eigen::Vector3d gyro_bias_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean_accel_mps2 = Eigen::Vector3d::Zero();
  int sample_count = 0;
  double duration_s = 0.0;
};

class StillnessDetector {
 public:
  explicit StillnessDetector(const StillnessThresholds& thresholds);

  // Adds a sample (stamps increasing); samples older than the window drop out.
  void add(const ImuSample& sample);
  void clear();

  // True when the window is full and quiet.
  bool isStill() const;
  // True when the window is full and not quiet.
  bool isMoving() const;

  // The alignment from the window's means, when it is still.
  std::optional<StaticAlignment> alignment() const;

 private:
  bool isFull() const;
  bool isQuiet() const;

  StillnessThresholds thresholds_;
  std::deque<ImuSample> window_;
  Eigen::Matrix<double, 6, 1> sum_ = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix<double, 6, 1> sum_squares_ = Eigen::Matrix<double, 6, 1>::Zero();
};

}  // namespace lineloc
