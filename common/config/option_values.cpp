#include "common/config/option_values.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace lineloc {
namespace {

void expectCount(const std::vector<double>& values, size_t count, const std::string& option,
                 const char* names) {
  if (values.size() != count) {
    throw std::invalid_argument(
        fmt::format("{} needs {} numbers: {} (got {})", option, count, names, values.size()));
  }
}

}  // namespace

std::optional<Eigen::Vector3d> pointOption(const std::vector<double>& values,
                                           const std::string& option) {
  if (values.empty()) {
    return std::nullopt;
  }
  expectCount(values, 3, option, "x y z");
  return Eigen::Vector3d(values[0], values[1], values[2]);
}

PoseWithCovariance poseOption(const std::vector<double>& values, double position_sigma_m,
                              double rotation_sigma_deg, const std::string& option) {
  expectCount(values, 7, option, "tx ty tz qx qy qz qw");
  const Eigen::Quaterniond rotation(values[6], values[3], values[4], values[5]);
  if (!(std::abs(rotation.norm() - 1.0) <= 1e-3)) {
    throw std::invalid_argument(
        fmt::format("{}: the quaternion qx qy qz qw is not of unit norm", option));
  }
  PoseWithCovariance pose;
  pose.pose = makePose({values[0], values[1], values[2]}, rotation.normalized());
  pose.covariance =
      diagonalPoseCovariance(position_sigma_m, rotation_sigma_deg * std::numbers::pi / 180.0);
  return pose;
}

std::optional<Sunlight> sunOption(const std::vector<double>& values, double ambient_fraction,
                                  const std::string& option) {
  if (values.empty()) {
    return std::nullopt;
  }
  expectCount(values, 2, option, "azimuth elevation (deg)");
  return Sunlight::fromAzimuthElevation(values[0], values[1], ambient_fraction);
}

}  // namespace lineloc
