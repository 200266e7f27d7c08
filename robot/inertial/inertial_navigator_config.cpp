#include "robot/inertial/inertial_navigator_config.h"

#include <fmt/format.h>

#include <stdexcept>

namespace lineloc {
namespace {

void requirePositive(double value, const char* name) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(
        fmt::format("inertial navigator: {} must be > 0, got {}", name, value));
  }
}

void requireNonNegative(double value, const char* name) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(
        fmt::format("inertial navigator: {} must be >= 0, got {}", name, value));
  }
}

}  // namespace

Eigen::Isometry3d InertialNavigatorConfig::defaultBodyCamera() {
  Eigen::Isometry3d T_body_camera = Eigen::Isometry3d::Identity();
  T_body_camera.linear() << 0.0, 0.0, 1.0, -1.0, 0.0, 0.0, 0.0, -1.0, 0.0;
  return T_body_camera;
}

void validate(const InertialNavigatorConfig& config) {
  requirePositive(config.gravity_mps2, "gravity_mps2");
  requirePositive(config.gyro_range_radps, "gyro_range_radps");
  requirePositive(config.accel_range_mps2, "accel_range_mps2");
  requirePositive(static_cast<double>(config.history_ns), "history_ns");
  requirePositive(config.gps_horizontal_sigma_m, "gps_horizontal_sigma_m");
  requirePositive(config.gps_vertical_sigma_m, "gps_vertical_sigma_m");
  requirePositive(config.max_ground_speed_mps, "max_ground_speed_mps");
  requirePositive(config.gps_velocity_sigma_mps, "gps_velocity_sigma_mps");
  requirePositive(config.compass_sigma_rad, "compass_sigma_rad");
  requireNonNegative(config.compass_bias_sigma_rad, "compass_bias_sigma_rad");
  requirePositive(config.zero_velocity_sigma_mps, "zero_velocity_sigma_mps");
  if (config.vision_error_correlation_m != 0.0) {
    requirePositive(config.vision_error_correlation_m, "vision_error_correlation_m");
    requirePositive(config.vision_error_correlation_rad, "vision_error_correlation_rad");
  }
  if (config.shared_fix_error_length_m != 0.0) {
    requirePositive(config.shared_fix_error_length_m, "shared_fix_error_length_m");
  }
  if (!config.R_body_imu.isUnitary(1e-6) || config.R_body_imu.determinant() < 0.0) {
    throw std::invalid_argument("inertial navigator: R_body_imu is not a rotation");
  }
  if (!(config.shared_fix_error_fraction >= 0.0 && config.shared_fix_error_fraction <= 1.0)) {
    throw std::invalid_argument(
        fmt::format("inertial navigator: shared_fix_error_fraction must be in [0, 1], got {}",
                    config.shared_fix_error_fraction));
  }
  if (!(config.gate_probability > 0.0 && config.gate_probability < 1.0)) {
    throw std::invalid_argument(fmt::format(
        "inertial navigator: gate_probability must be in (0, 1), got {}", config.gate_probability));
  }
}

double compassYawSigma_rad(const InertialNavigatorConfig& config) {
  return std::hypot(config.compass_sigma_rad, config.compass_bias_sigma_rad);
}

Eigen::Vector3d gpsFixSigmas(const GpsFix& fix, const InertialNavigatorConfig& config) {
  const double horizontal =
      fix.horizontal_sigma_m > 0.0 ? fix.horizontal_sigma_m : config.gps_horizontal_sigma_m;
  const double vertical =
      fix.vertical_sigma_m > 0.0 ? fix.vertical_sigma_m : config.gps_vertical_sigma_m;
  return {horizontal, horizontal, vertical};
}

}  // namespace lineloc
