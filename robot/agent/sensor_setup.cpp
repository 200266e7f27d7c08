#include "robot/agent/sensor_setup.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "common/geometry/pose.h"

namespace lineloc {
namespace {

// The IMU noise of `setup`: nullopt when none of the four is configured.
std::optional<ImuNoiseDensities> configuredImuNoise(const SensorSetup& setup) {
  const std::array<std::pair<const char*, double>, 4> densities = {
      {{"gyro_noise_density", setup.gyro_noise_density},
       {"accel_noise_density", setup.accel_noise_density},
       {"gyro_random_walk", setup.gyro_random_walk},
       {"accel_random_walk", setup.accel_random_walk}}};
  int given = 0;
  for (const auto& [name, value] : densities) {
    given += value != 0.0 ? 1 : 0;
  }
  if (given == 0) {
    return std::nullopt;
  }
  for (const auto& [name, value] : densities) {
    if (!(std::isfinite(value) && value > 0.0)) {
      throw std::invalid_argument(
          fmt::format("{} must be a positive density when any of the IMU's noise is configured "
                      "(all four are needed), not {}",
                      name, value));
    }
  }
  return ImuNoiseDensities{setup.gyro_noise_density, setup.accel_noise_density,
                           setup.gyro_random_walk, setup.accel_random_walk};
}

// A range option: 0 leaves `range` as it is.
void applyRange(const char* name, double configured, double& range) {
  if (!(std::isfinite(configured) && configured >= 0.0)) {
    throw std::invalid_argument(fmt::format("{} must be 0 or positive, not {}", name, configured));
  }
  if (configured > 0.0) {
    range = configured;
  }
}

// A pose option (16 numbers), else the dataset's, else nullopt.
std::optional<Eigen::Isometry3d> configuredPose(const char* name,
                                                const std::vector<double>& configured,
                                                const std::optional<Eigen::Isometry3d>& dataset) {
  if (configured.empty()) {
    return dataset;
  }
  try {
    return rigidTransform(configured, name);
  } catch (const std::runtime_error& error) {
    throw std::invalid_argument(error.what());
  }
}

}  // namespace

void applySensorSetup(const SensorSetup& setup, const SensorStreams& streams,
                      const std::optional<KalibrCamera>& camchain,
                      InertialNavigatorConfig& navigator) {
  if (const std::optional<ImuNoiseDensities> noise = configuredImuNoise(setup)) {
    navigator.imu_noise = *noise;
  } else if (streams.imu_noise) {
    navigator.imu_noise = *streams.imu_noise;
  }
  applyRange("gyro_range_radps", setup.gyro_range_radps, navigator.gyro_range_radps);
  applyRange("accel_range_mps2", setup.accel_range_mps2, navigator.accel_range_mps2);
  const std::optional<Eigen::Isometry3d> T_body_imu =
      configuredPose("T_body_imu", setup.T_body_imu, streams.T_body_imu);
  if (T_body_imu) {
    navigator.R_body_imu = T_body_imu->linear();
  }
  std::optional<Eigen::Isometry3d> T_body_camera = streams.T_body_camera;
  if (camchain && camchain->T_cam_imu) {
    T_body_camera =
        T_body_imu.value_or(Eigen::Isometry3d::Identity()) * camchain->T_cam_imu->inverse();
  }
  if (const auto camera = configuredPose("T_body_camera", setup.T_body_camera, T_body_camera)) {
    navigator.T_body_camera = *camera;
  }
  if (setup.p_body_gps_antenna.size() != 3 ||
      !Eigen::Map<const Eigen::Vector3d>(setup.p_body_gps_antenna.data()).allFinite()) {
    throw std::invalid_argument("p_body_gps_antenna must be three finite numbers, x y z (m)");
  }
  navigator.p_body_gps_antenna = Eigen::Map<const Eigen::Vector3d>(setup.p_body_gps_antenna.data());
}

int64_t cameraTimeOffsetNs(const SensorSetup& setup, const std::optional<KalibrCamera>& camchain) {
  if (!(std::isfinite(setup.camera_time_offset_s) && std::abs(setup.camera_time_offset_s) < 1e6)) {
    throw std::invalid_argument("camera_time_offset_s must be a finite number of seconds");
  }
  const double shift_s = camchain ? camchain->timeshift_cam_imu_s : 0.0;
  return std::llround((setup.camera_time_offset_s - shift_s) * 1e9);
}

}  // namespace lineloc
