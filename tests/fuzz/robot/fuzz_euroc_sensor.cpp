// Fuzz target: EuRoC/ASL sensor.yaml files, their T_BS block and an IMU's noise.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>

#include "robot/input/euroc_sensor.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream stream(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const Eigen::Isometry3d T_body_sensor = lineloc::parseEurocSensorPose(stream, "fuzz.yaml");
    if (!T_body_sensor.matrix().allFinite()) {
      __builtin_trap();
    }
  } catch (const std::runtime_error&) {
  }
  std::istringstream imu(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const std::optional<lineloc::ImuNoiseDensities> noise =
        lineloc::parseEurocImuNoise(imu, "fuzz.yaml");
    if (noise && !(noise->gyro_noise_radps_per_sqrt_hz > 0.0 &&
                   noise->gyro_bias_random_walk_radps2_per_sqrt_hz > 0.0 &&
                   noise->accel_noise_mps2_per_sqrt_hz > 0.0 &&
                   noise->accel_bias_random_walk_mps3_per_sqrt_hz > 0.0)) {
      __builtin_trap();
    }
  } catch (const std::runtime_error&) {
  }
  return 0;
}
