// A pose as the seven numbers a pose option takes (poseOption,
// common/config/option_values.h): tx ty tz qx qy qz qw.
#pragma once

#include <Eigen/Geometry>
#include <vector>

namespace lineloc::test {

inline std::vector<double> poseOptionValues(const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond rotation(pose.linear());
  return {pose.translation().x(),
          pose.translation().y(),
          pose.translation().z(),
          rotation.x(),
          rotation.y(),
          rotation.z(),
          rotation.w()};
}

}  // namespace lineloc::test
