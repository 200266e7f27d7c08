#include "robot/input/euroc_sensor.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <fstream>
#include <functional>
#include <stdexcept>

#include "common/config/yaml_document.h"
#include "common/geometry/pose.h"

namespace lineloc {
namespace {

std::vector<double> poseEntries(const YAML::Node& root, const std::string& source) {
  const YAML::Node block = root["T_BS"];
  if (!block || !block.IsMap()) {
    throw std::runtime_error(fmt::format("{}: no T_BS block", source));
  }
  if (!block["rows"] || !block["cols"] || block["rows"].as<int>() != 4 ||
      block["cols"].as<int>() != 4) {
    throw std::runtime_error(fmt::format("{}: T_BS must have rows: 4 and cols: 4", source));
  }
  const YAML::Node data = block["data"];
  if (!data || !data.IsSequence() || data.size() != 16) {
    throw std::runtime_error(fmt::format("{}: T_BS data must hold 16 numbers", source));
  }
  std::vector<double> entries;
  for (const YAML::Node& value : data) {
    entries.push_back(value.as<double>());
  }
  return entries;
}

// The document of `yaml`, parsed by `read`, with yaml-cpp's errors named by `source`.
template <typename T>
T readDocument(std::istream& yaml, const std::string& source,
               const std::function<T(const YAML::Node&)>& read) {
  try {
    return read(loadYamlDocument(yaml, source));
  } catch (const YAML::Exception& error) {
    throw std::runtime_error(fmt::format("{}: {}", source, error.what()));
  }
}

std::ifstream openFile(const std::string& path) {
  std::ifstream stream(path);
  if (!stream) {
    throw std::runtime_error(fmt::format("cannot open '{}'", path));
  }
  return stream;
}

}  // namespace

Eigen::Isometry3d parseEurocSensorPose(std::istream& yaml, const std::string& source) {
  const std::vector<double> entries = readDocument<std::vector<double>>(
      yaml, source, [&](const YAML::Node& root) { return poseEntries(root, source); });
  return rigidTransform(entries, source + ": T_BS");
}

Eigen::Isometry3d readEurocSensorPose(const std::string& path) {
  std::ifstream stream = openFile(path);
  return parseEurocSensorPose(stream, path);
}

std::optional<ImuNoiseDensities> parseEurocImuNoise(std::istream& yaml, const std::string& source) {
  return readDocument<std::optional<ImuNoiseDensities>>(
      yaml, source, [&](const YAML::Node& root) -> std::optional<ImuNoiseDensities> {
        ImuNoiseDensities noise;
        const std::array<std::pair<const char*, double*>, 4> keys = {
            {{"gyroscope_noise_density", &noise.gyro_noise_radps_per_sqrt_hz},
             {"gyroscope_random_walk", &noise.gyro_bias_random_walk_radps2_per_sqrt_hz},
             {"accelerometer_noise_density", &noise.accel_noise_mps2_per_sqrt_hz},
             {"accelerometer_random_walk", &noise.accel_bias_random_walk_mps3_per_sqrt_hz}}};
        int given = 0;
        for (const auto& [key, value] : keys) {
          given += root.IsMap() && root[key] ? 1 : 0;
        }
        if (given == 0) {
          return std::nullopt;
        }
        for (const auto& [key, value] : keys) {
          if (!root[key]) {
            throw std::runtime_error(fmt::format(
                "{}: {} is missing: an IMU's noise needs all four densities", source, key));
          }
          *value = root[key].as<double>();
          if (!std::isfinite(*value) || *value <= 0.0) {
            throw std::runtime_error(
                fmt::format("{}: {} must be a positive number, not {}", source, key, *value));
          }
        }
        return noise;
      });
}

std::optional<ImuNoiseDensities> readEurocImuNoise(const std::string& path) {
  std::ifstream stream = openFile(path);
  return parseEurocImuNoise(stream, path);
}

}  // namespace lineloc
