// Distances between points and segments, and whether one segment runs along
// another: the tests that associate, merge and score line segments share.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

namespace lineloc {

// Distance from `point` to the segment a-b (to a when it has no length).
template <int N>
double distanceToSegment(const Eigen::Matrix<double, N, 1>& point,
                         const Eigen::Matrix<double, N, 1>& a,
                         const Eigen::Matrix<double, N, 1>& b) {
  const Eigen::Matrix<double, N, 1> ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((point - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + t * ab - point).norm();
}

// Distance from `point` to the polyline through `points`: to the nearest of
// its segments (to its one point; infinity when it has none).
double distanceToPolyline(const Eigen::Vector2d& point, const std::vector<Eigen::Vector2d>& points);

// Whether segment b runs along segment a: within max_angle_rad of a's
// direction, both its ends within max_distance_m of a's line, and the two
// overlapping along it. False for an a of no length.
bool runsAlong(const Eigen::Vector3d& a_start, const Eigen::Vector3d& a_end,
               const Eigen::Vector3d& b_start, const Eigen::Vector3d& b_end, double max_angle_rad,
               double max_distance_m);

}  // namespace lineloc
