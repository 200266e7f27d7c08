// Values the programs' options give as lists of numbers, checked and turned
// into what they name: a point (x y z, e.g. a site origin), a pose with its
// standard deviations (tx ty tz qx qy qz qw) and the sun (azimuth elevation).
// A wrong count throws std::invalid_argument naming the option, so a YAML
// file that gives two numbers for three is refused, not read past its end.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "common/geometry/pose.h"
#include "common/geometry/sunlight.h"

namespace lineloc {

// Empty: nullopt; x y z: the point.
std::optional<Eigen::Vector3d> pointOption(const std::vector<double>& values,
                                           const std::string& option);

// tx ty tz qx qy qz qw, the quaternion of unit norm (within 1e-3), with a
// diagonal covariance of the two standard deviations.
PoseWithCovariance poseOption(const std::vector<double>& values, double position_sigma_m,
                              double rotation_sigma_deg, const std::string& option);

// Empty: nullopt (the sun unknown); azimuth clockwise from grid north and
// elevation (deg): the sun, with `ambient_fraction` of the light in the shade.
std::optional<Sunlight> sunOption(const std::vector<double>& values, double ambient_fraction,
                                  const std::string& option);

}  // namespace lineloc
