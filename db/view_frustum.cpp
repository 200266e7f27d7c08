#include "db/view_frustum.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

// The ray of pixel (u, v) at depth 1, camera frame.
Eigen::Vector3d backProject(const PinholeCamera& camera, double u, double v) {
  const double y = (v - camera.cy) / camera.fy;
  return {(u - camera.cx - camera.skew * y) / camera.fx, y, 1.0};
}

}  // namespace

ViewFrustum::ViewFrustum(const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera,
                         double near_m, double far_m) {
  checkInput(T_world_camera, camera, near_m, far_m);
  const double w = camera.width;
  const double h = camera.height;
  const std::array<Eigen::Vector3d, 4> corner_rays = {
      backProject(camera, 0, 0), backProject(camera, w, 0), backProject(camera, w, h),
      backProject(camera, 0, h)};
  const Eigen::Vector3d centre_ray = backProject(camera, 0.5 * w, 0.5 * h);
  std::array<Eigen::Vector4d, 6> planes_camera;
  for (size_t i = 0; i < 4; ++i) {
    Eigen::Vector3d normal = corner_rays[i].cross(corner_rays[(i + 1) % 4]).normalized();
    if (normal.dot(centre_ray) < 0.0) {
      normal = -normal;
    }
    planes_camera[i] << normal, 0.0;
  }
  planes_camera[4] << 0.0, 0.0, 1.0, -near_m;
  planes_camera[5] << 0.0, 0.0, -1.0, far_m;
  const Eigen::Matrix3d R = T_world_camera.linear();
  const Eigen::Vector3d t = T_world_camera.translation();
  for (size_t i = 0; i < planes_camera.size(); ++i) {
    const Eigen::Vector3d normal_world = R * planes_camera[i].head<3>();
    planes_world_[i] << normal_world, planes_camera[i].w() - normal_world.dot(t);
  }
  for (const Eigen::Vector3d& ray : corner_rays) {
    bounds_world_.extend(T_world_camera * (near_m * ray));
    bounds_world_.extend(T_world_camera * (far_m * ray));
  }
}

bool ViewFrustum::meetsSegment(const Eigen::Vector3d& a_world,
                               const Eigen::Vector3d& b_world) const {
  // Inside plane i where f_i(s) = f_i(a) + s (f_i(b) - f_i(a)) >= 0.
  double s_enter = 0.0;
  double s_leave = 1.0;
  for (const Eigen::Vector4d& plane : planes_world_) {
    const double at_a = plane.head<3>().dot(a_world) + plane.w();
    const double at_b = plane.head<3>().dot(b_world) + plane.w();
    if (at_a < 0.0 && at_b < 0.0) {
      return false;
    }
    if (at_a < 0.0) {
      s_enter = std::max(s_enter, at_a / (at_a - at_b));
    } else if (at_b < 0.0) {
      s_leave = std::min(s_leave, at_a / (at_a - at_b));
    }
    if (s_enter > s_leave) {
      return false;
    }
  }
  return true;
}

}  // namespace lineloc::db
