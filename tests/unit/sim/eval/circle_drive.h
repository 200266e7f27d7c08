// Ground truth for evaluation tests: a camera driving a 20 m radius circle at
// 2 m/s (at angle 0 at time 1 s), sampled at `rate_hz` for `duration_s` from
// `start_ns`, yawing with the motion.
#pragma once

#include <cmath>
#include <vector>

#include "common/trajectory/tum_trajectory.h"

namespace lineloc {

inline std::vector<StampedPose> circleDrive(double rate_hz, double duration_s,
                                            int64_t start_ns = 1'000'000'000) {
  constexpr double kRadius_m = 20.0;
  constexpr double kSpeed_m_s = 2.0;
  std::vector<StampedPose> poses;
  const int count = static_cast<int>(rate_hz * duration_s) + 1;
  for (int i = 0; i < count; ++i) {
    StampedPose pose;
    pose.stamp_ns = start_ns + static_cast<int64_t>(std::llround(i / rate_hz * 1e9));
    const double angle =
        kSpeed_m_s * static_cast<double>(pose.stamp_ns - 1'000'000'000) / 1e9 / kRadius_m;
    pose.pose.linear() =
        Eigen::AngleAxisd(angle + M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose.pose.translation() =
        Eigen::Vector3d(kRadius_m * std::cos(angle), kRadius_m * std::sin(angle), 1.5);
    poses.push_back(pose);
  }
  return poses;
}

}  // namespace lineloc
