#include "common/geometry/polygon_triangulation.h"

#include <Eigen/Geometry>
#include <numeric>

namespace lineloc {
namespace {

constexpr double kMinAreaRatio = 1e-12;

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// True when p lies inside or on triangle (a, b, c), counter-clockwise.
bool inTriangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                const Eigen::Vector2d& c) {
  return cross2(b - a, p - a) >= 0.0 && cross2(c - b, p - c) >= 0.0 && cross2(a - c, p - a) >= 0.0;
}

// Coordinates of the ring in its plane, with the Newell normal as +z.
std::vector<Eigen::Vector2d> projectToPlane(const std::vector<Eigen::Vector3d>& ring,
                                            const Eigen::Vector3d& normal) {
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector3d helper =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d u = n.cross(helper).normalized();
  const Eigen::Vector3d v = n.cross(u);
  std::vector<Eigen::Vector2d> points;
  points.reserve(ring.size());
  for (const Eigen::Vector3d& p : ring) {
    points.emplace_back(p.dot(u), p.dot(v));
  }
  return points;
}

bool isEar(const std::vector<Eigen::Vector2d>& points, const std::vector<int>& remaining,
           size_t i) {
  const size_t n = remaining.size();
  const Eigen::Vector2d& a = points[remaining[(i + n - 1) % n]];
  const Eigen::Vector2d& b = points[remaining[i]];
  const Eigen::Vector2d& c = points[remaining[(i + 1) % n]];
  if (cross2(b - a, c - b) <= 0.0) {
    return false;  // reflex or degenerate corner
  }
  for (size_t k = 0; k < n; ++k) {
    if (k == i || k == (i + 1) % n || k == (i + n - 1) % n) {
      continue;
    }
    const Eigen::Vector2d& p = points[remaining[k]];
    if (p != a && p != b && p != c && inTriangle(p, a, b, c)) {
      return false;
    }
  }
  return true;
}

}  // namespace

Eigen::Vector3d newellNormal(const std::vector<Eigen::Vector3d>& ring) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  if (ring.empty()) {
    return normal;
  }
  // Relative to the first vertex, so large projected coordinates lose no precision.
  const Eigen::Vector3d& reference = ring.front();
  for (size_t i = 0; i < ring.size(); ++i) {
    normal += (ring[i] - reference).cross(ring[(i + 1) % ring.size()] - reference);
  }
  return normal;
}

std::vector<std::array<int, 3>> triangulatePolygon(const std::vector<Eigen::Vector3d>& ring) {
  std::vector<std::array<int, 3>> triangles;
  if (ring.size() < 3) {
    return triangles;
  }
  const Eigen::Vector3d normal = newellNormal(ring);
  double extent = 0.0;
  for (const Eigen::Vector3d& p : ring) {
    extent = std::max(extent, (p - ring.front()).squaredNorm());
  }
  if (!normal.allFinite() || normal.norm() <= kMinAreaRatio * extent) {
    return triangles;
  }
  const std::vector<Eigen::Vector2d> points = projectToPlane(ring, normal);
  std::vector<int> remaining(ring.size());
  std::iota(remaining.begin(), remaining.end(), 0);
  while (remaining.size() > 3) {
    size_t ear = 0;
    while (ear < remaining.size() && !isEar(points, remaining, ear)) {
      ++ear;
    }
    if (ear == remaining.size()) {
      ear = 0;  // no strict ear (self-touching ring): clip anyway, never loop forever
    }
    const size_t n = remaining.size();
    triangles.push_back({remaining[(ear + n - 1) % n], remaining[ear], remaining[(ear + 1) % n]});
    remaining.erase(remaining.begin() + static_cast<long>(ear));
  }
  triangles.push_back({remaining[0], remaining[1], remaining[2]});
  return triangles;
}

}  // namespace lineloc
