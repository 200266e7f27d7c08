#include "robot/input/euroc_sensor.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "common/config/yaml_document.h"

namespace lineloc {
namespace {

constexpr double kOrthonormalityTolerance = 1e-6;

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
    if (!std::isfinite(entries.back())) {
      throw std::runtime_error(fmt::format("{}: T_BS data holds a non-finite number", source));
    }
  }
  return entries;
}

}  // namespace

Eigen::Isometry3d parseEurocSensorPose(std::istream& yaml, const std::string& source) {
  std::vector<double> entries;
  try {
    entries = poseEntries(loadYamlDocument(yaml, source), source);
  } catch (const YAML::Exception& error) {
    throw std::runtime_error(fmt::format("{}: {}", source, error.what()));
  }
  const Eigen::Matrix4d T =
      Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(entries.data());
  if (!T.row(3).isApprox(Eigen::RowVector4d(0.0, 0.0, 0.0, 1.0), kOrthonormalityTolerance)) {
    throw std::runtime_error(fmt::format("{}: T_BS last row must be 0 0 0 1", source));
  }
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  if (!(R.transpose() * R).isIdentity(kOrthonormalityTolerance) ||
      std::abs(R.determinant() - 1.0) > kOrthonormalityTolerance) {
    throw std::runtime_error(fmt::format("{}: T_BS rotation is not a proper rotation", source));
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = R;
  pose.translation() = T.topRightCorner<3, 1>();
  return pose;
}

Eigen::Isometry3d readEurocSensorPose(const std::string& path) {
  std::ifstream stream(path);
  if (!stream) {
    throw std::runtime_error(fmt::format("cannot open '{}'", path));
  }
  return parseEurocSensorPose(stream, path);
}

}  // namespace lineloc
