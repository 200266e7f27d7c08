#include "tests/unit/common/pose/opencv_pnp.h"

#include <opencv2/calib3d.hpp>
#include <vector>

namespace lineloc::test {

Eigen::Isometry3d worldCameraFromRvecTvec(const Eigen::Vector3d& rvec,
                                          const Eigen::Vector3d& tvec) {
  Eigen::Isometry3d T_camera_world = Eigen::Isometry3d::Identity();
  const double angle = rvec.norm();
  if (angle > 0.0) {
    T_camera_world.linear() = Eigen::AngleAxisd(angle, rvec / angle).toRotationMatrix();
  }
  T_camera_world.translation() = tvec;
  return T_camera_world.inverse();
}

std::optional<Eigen::Isometry3d> solvePnPOpenCv(const PoseProblem& problem, int flag) {
  std::vector<cv::Point3d> object_points;
  std::vector<cv::Point2d> image_points;
  for (const auto& point : problem.points) {
    object_points.emplace_back(point.p_world.x(), point.p_world.y(), point.p_world.z());
    image_points.emplace_back(point.pixel.x(), point.pixel.y());
  }
  const PinholeCamera& camera = problem.camera;
  const cv::Matx33d K(camera.fx, camera.skew, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0);
  cv::Vec3d rvec;
  cv::Vec3d tvec;
  if (!cv::solvePnP(object_points, image_points, K, cv::noArray(), rvec, tvec, false, flag)) {
    return std::nullopt;
  }
  return worldCameraFromRvecTvec({rvec[0], rvec[1], rvec[2]}, {tvec[0], tvec[1], tvec[2]});
}

}  // namespace lineloc::test
