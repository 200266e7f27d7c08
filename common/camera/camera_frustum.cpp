#include "common/camera/camera_frustum.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace lineloc {
namespace {

Eigen::Vector3d backProject(const PinholeCamera& camera, double u, double v) {
  const double y = (v - camera.cy) / camera.fy;
  return {(u - camera.cx - camera.skew * y) / camera.fx, y, 1.0};
}

}  // namespace

std::array<Eigen::Vector3d, 4> imageCornerRays(const PinholeCamera& camera, double margin_px) {
  const double low = -margin_px;
  const double right = camera.width + margin_px;
  const double bottom = camera.height + margin_px;
  return {backProject(camera, low, low), backProject(camera, right, low),
          backProject(camera, right, bottom), backProject(camera, low, bottom)};
}

HalfSpaces cameraFrustum(const PinholeCamera& camera, double near_m, double far_m,
                         double margin_px) {
  const std::array<Eigen::Vector3d, 4> corners = imageCornerRays(camera, margin_px);
  const Eigen::Vector3d centre = backProject(camera, 0.5 * camera.width, 0.5 * camera.height);
  HalfSpaces planes;
  for (size_t i = 0; i < corners.size(); ++i) {
    Eigen::Vector3d normal = corners[i].cross(corners[(i + 1) % corners.size()]).normalized();
    if (normal.dot(centre) < 0.0) {
      normal = -normal;
    }
    planes[i] << normal, 0.0;
  }
  planes[4] << 0.0, 0.0, 1.0, -near_m;
  planes[5] << 0.0, 0.0, -1.0, far_m;
  return planes;
}

std::optional<std::array<double, 2>> clipSegment(const HalfSpaces& planes, const Eigen::Vector3d& a,
                                                 const Eigen::Vector3d& b) {
  double s_enter = 0.0;
  double s_leave = 1.0;
  for (const Eigen::Vector4d& plane : planes) {
    const double at_a = plane.head<3>().dot(a) + plane.w();
    const double at_b = plane.head<3>().dot(b) + plane.w();
    if (at_a < 0.0 && at_b < 0.0) {
      return std::nullopt;
    }
    if (at_a < 0.0) {
      s_enter = std::max(s_enter, at_a / (at_a - at_b));
    } else if (at_b < 0.0) {
      s_leave = std::min(s_leave, at_a / (at_a - at_b));
    }
  }
  if (s_enter > s_leave) {
    return std::nullopt;
  }
  return std::array<double, 2>{s_enter, s_leave};
}

}  // namespace lineloc
