// What an EuRoC/ASL dataset's sensor.yaml says of its sensor (Burri et al.,
// "The EuRoC micro aerial vehicle datasets", IJRR 2016): its mounting, the
// T_BS block, the sensor's pose in the body frame as a row-major 4x4 matrix;
// and of an IMU, its noise as continuous-time densities under the keys
// EuRoC and Kalibr share (gyroscope_noise_density rad/s/sqrt(Hz),
// gyroscope_random_walk rad/s^2/sqrt(Hz), accelerometer_noise_density
// m/s^2/sqrt(Hz), accelerometer_random_walk m/s^3/sqrt(Hz)).
#pragma once

#include <Eigen/Geometry>
#include <istream>
#include <optional>
#include <string>
#include <vector>

#include "robot/inertial/imu_sample.h"

namespace lineloc {

// Parses T_BS (rows: 4, cols: 4, data: 16 numbers) from sensor.yaml text;
// `source` names it in errors. Throws std::runtime_error when the block is
// missing or malformed, or is not a rigid transform (rigidTransform, pose.h).
Eigen::Isometry3d parseEurocSensorPose(std::istream& yaml, const std::string& source);

// The same for a file.
Eigen::Isometry3d readEurocSensorPose(const std::string& path);

// The four noise densities of an IMU's sensor.yaml text; nullopt when it
// holds none of them. Throws std::runtime_error naming `source` and the key
// when it holds some but not all, or one that is not a positive finite
// number.
std::optional<ImuNoiseDensities> parseEurocImuNoise(std::istream& yaml, const std::string& source);

// The same for a file.
std::optional<ImuNoiseDensities> readEurocImuNoise(const std::string& path);

}  // namespace lineloc
