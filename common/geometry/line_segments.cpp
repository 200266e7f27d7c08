#include "common/geometry/line_segments.h"

#include <Eigen/Geometry>
#include <limits>

namespace lineloc {

double distanceToPolyline(const Eigen::Vector2d& point,
                          const std::vector<Eigen::Vector2d>& points) {
  if (points.size() == 1) {
    return (point - points.front()).norm();
  }
  double nearest = std::numeric_limits<double>::infinity();
  for (size_t i = 1; i < points.size(); ++i) {
    nearest = std::min(nearest, distanceToSegment<2>(point, points[i - 1], points[i]));
  }
  return nearest;
}

bool runsAlong(const Eigen::Vector3d& a_start, const Eigen::Vector3d& a_end,
               const Eigen::Vector3d& b_start, const Eigen::Vector3d& b_end, double max_angle_rad,
               double max_distance_m) {
  const Eigen::Vector3d along = a_end - a_start;
  const double length = along.norm();
  if (!(length > 1e-9)) {
    return false;
  }
  const Eigen::Vector3d direction = along / length;
  if (direction.cross((b_end - b_start).normalized()).norm() > std::sin(max_angle_rad)) {
    return false;
  }
  const auto across = [&](const Eigen::Vector3d& point) {
    const Eigen::Vector3d offset = point - a_start;
    return (offset - offset.dot(direction) * direction).norm();
  };
  if (across(b_start) > max_distance_m || across(b_end) > max_distance_m) {
    return false;
  }
  const double s0 = direction.dot(b_start - a_start);
  const double s1 = direction.dot(b_end - a_start);
  return std::max(s0, s1) > 0.0 && std::min(s0, s1) < length;
}

}  // namespace lineloc
