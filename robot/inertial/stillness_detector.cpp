#include "robot/inertial/stillness_detector.h"

#include <cmath>

namespace lineloc {
namespace {

Eigen::Matrix<double, 6, 1> stacked(const ImuSample& sample) {
  Eigen::Matrix<double, 6, 1> x;
  x << sample.gyro_radps, sample.accel_mps2;
  return x;
}

}  // namespace

StillnessDetector::StillnessDetector(const StillnessThresholds& thresholds)
    : thresholds_(thresholds) {}

void StillnessDetector::add(const ImuSample& sample) {
  const Eigen::Matrix<double, 6, 1> x = stacked(sample);
  window_.push_back(sample);
  sum_ += x;
  sum_squares_ += x.cwiseProduct(x);
  while (window_.back().stamp_ns - window_.front().stamp_ns > thresholds_.window_ns) {
    const Eigen::Matrix<double, 6, 1> old = stacked(window_.front());
    sum_ -= old;
    sum_squares_ -= old.cwiseProduct(old);
    window_.pop_front();
  }
}

void StillnessDetector::clear() {
  window_.clear();
  sum_.setZero();
  sum_squares_.setZero();
}

bool StillnessDetector::isFull() const {
  // A window is full when its span reaches 90 % of the length (sample jitter).
  return window_.size() >= 2 &&
         10 * (window_.back().stamp_ns - window_.front().stamp_ns) >= 9 * thresholds_.window_ns;
}

bool StillnessDetector::isMoving() const {
  return isFull() && !isQuiet();
}

bool StillnessDetector::isStill() const {
  return isFull() && isQuiet();
}

bool StillnessDetector::isQuiet() const {
  const double n = static_cast<double>(window_.size());
  const Eigen::Matrix<double, 6, 1> mean = sum_ / n;
  const Eigen::Matrix<double, 6, 1> variance =
      (sum_squares_ / n - mean.cwiseProduct(mean)).cwiseMax(0.0);
  const double gyro_limit = thresholds_.gyro_std_radps * thresholds_.gyro_std_radps;
  const double accel_limit = thresholds_.accel_std_mps2 * thresholds_.accel_std_mps2;
  return variance.head<3>().maxCoeff() < gyro_limit && variance.tail<3>().maxCoeff() < accel_limit;
}

std::optional<StaticAlignment> StillnessDetector::alignment() const {
  if (!isStill()) {
    return std::nullopt;
  }
  const Eigen::Matrix<double, 6, 1> mean = sum_ / static_cast<double>(window_.size());
  StaticAlignment alignment;
  alignment.gyro_bias_radps = mean.head<3>();
  alignment.mean_accel_mps2 = mean.tail<3>();
  const Eigen::Vector3d& f = alignment.mean_accel_mps2;
  alignment.roll_rad = std::atan2(f.y(), f.z());
  alignment.pitch_rad = std::atan2(-f.x(), std::hypot(f.y(), f.z()));
  alignment.sample_count = static_cast<int>(window_.size());
  alignment.duration_s =
      static_cast<double>(window_.back().stamp_ns - window_.front().stamp_ns) * 1e-9;
  return alignment;
}

}  // namespace lineloc
