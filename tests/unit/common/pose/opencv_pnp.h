// cv::solvePnP on a PoseProblem's points, the baseline users would pick,
// with OpenCV's (rvec, tvec) = T_camera_world converted to T_world_camera.
#pragma once

#include <Eigen/Geometry>
#include <optional>

#include "common/pose/pose_problem.h"

namespace lineloc::test {

// T_world_camera from an OpenCV rotation vector and translation (T_camera_world).
Eigen::Isometry3d worldCameraFromRvecTvec(const Eigen::Vector3d& rvec, const Eigen::Vector3d& tvec);

// flag is a cv::SolvePnPMethod; nullopt when OpenCV reports failure.
std::optional<Eigen::Isometry3d> solvePnPOpenCv(const PoseProblem& problem, int flag);

}  // namespace lineloc::test
