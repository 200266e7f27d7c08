#include "db/view_frustum.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "common/camera/camera_frustum.h"

namespace lineloc::db {
namespace {

void checkInput(const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera, double near_m,
                double far_m) {
  if (!T_world_camera.matrix().allFinite()) {
    throw std::invalid_argument("view frustum: the camera pose is not finite");
  }
  if (!(camera.fx > 0.0 && camera.fy > 0.0 && std::isfinite(camera.fx) &&
        std::isfinite(camera.fy) && std::isfinite(camera.cx) && std::isfinite(camera.cy) &&
        std::isfinite(camera.skew) && camera.width > 0 && camera.height > 0)) {
    throw std::invalid_argument(fmt::format(
        "view frustum: camera needs finite fx, fy > 0 and a positive image size (fx {} fy {} "
        "size {}x{})",
        camera.fx, camera.fy, camera.width, camera.height));
  }
  if (!(near_m > 0.0 && far_m > near_m && std::isfinite(far_m))) {
    throw std::invalid_argument(
        fmt::format("view frustum: needs 0 < near < far, got near {} m, far {} m", near_m, far_m));
  }
}

}  // namespace

ViewFrustum::ViewFrustum(const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera,
                         double near_m, double far_m) {
  checkInput(T_world_camera, camera, near_m, far_m);
  const HalfSpaces planes_camera = cameraFrustum(camera, near_m, far_m);
  const Eigen::Matrix3d R = T_world_camera.linear();
  const Eigen::Vector3d t = T_world_camera.translation();
  for (size_t i = 0; i < planes_camera.size(); ++i) {
    const Eigen::Vector3d normal_world = R * planes_camera[i].head<3>();
    planes_world_[i] << normal_world, planes_camera[i].w() - normal_world.dot(t);
  }
  for (const Eigen::Vector3d& ray : imageCornerRays(camera, 0.0)) {
    bounds_world_.extend(T_world_camera * (near_m * ray));
    bounds_world_.extend(T_world_camera * (far_m * ray));
  }
}

bool ViewFrustum::meetsSegment(const Eigen::Vector3d& a_world,
                               const Eigen::Vector3d& b_world) const {
  return clipSegment(planes_world_, a_world, b_world).has_value();
}

}  // namespace lineloc::db
