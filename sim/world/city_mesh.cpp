#include "sim/world/city_mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "db/citymodel/cityjson_reader.h"
#include "db/citymodel/polygon_geometry.h"

namespace lineloc {
namespace {

// Twice the signed area of triangle abc in the plane.
double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d ab = b - a;
  const Eigen::Vector2d ac = c - a;
  return ab.x() * ac.y() - ab.y() * ac.x();
}

bool insideTriangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                    const Eigen::Vector2d& c) {
  return cross2(a, b, p) >= 0.0 && cross2(b, c, p) >= 0.0 && cross2(c, a, p) >= 0.0;
}

// The ring in 2D, dropping the normal's dominant axis and keeping the winding
// counter-clockwise.
std::vector<Eigen::Vector2d> projectRing(const std::vector<Eigen::Vector3d>& ring,
                                         const Eigen::Vector3d& normal) {
  int drop = 0;
  normal.cwiseAbs().maxCoeff(&drop);
  const int u = (drop + 1) % 3;
  const int v = (drop + 2) % 3;
  const bool flip = normal[drop] < 0.0;
  std::vector<Eigen::Vector2d> points;
  for (const Eigen::Vector3d& p : ring) {
    points.emplace_back(p[u], flip ? -p[v] : p[v]);
  }
  return points;
}

bool isEar(const std::vector<Eigen::Vector2d>& points, const std::vector<int>& polygon, size_t i) {
  const size_t n = polygon.size();
  const Eigen::Vector2d& a = points[polygon[(i + n - 1) % n]];
  const Eigen::Vector2d& b = points[polygon[i]];
  const Eigen::Vector2d& c = points[polygon[(i + 1) % n]];
  if (cross2(a, b, c) <= 0.0) {
    return false;  // reflex or flat corner
  }
  for (size_t k = 0; k < n; ++k) {
    const int other = polygon[k];
    if (other != polygon[(i + n - 1) % n] && other != polygon[i] && other != polygon[(i + 1) % n] &&
        insideTriangle(points[other], a, b, c)) {
      return false;
    }
  }
  return true;
}

SurfaceKind sceneKind(citymodel::SurfaceKind kind) {
  return kind == citymodel::SurfaceKind::kRoof ? SurfaceKind::kRoof : SurfaceKind::kWall;
}

}  // namespace

std::vector<std::array<int, 3>> triangulateRing(const std::vector<Eigen::Vector3d>& ring,
                                                const Eigen::Vector3d& normal) {
  std::vector<std::array<int, 3>> triangles;
  if (ring.size() < 3 || !(normal.norm() > 0.0)) {
    return triangles;
  }
  const std::vector<Eigen::Vector2d> points = projectRing(ring, normal);
  std::vector<int> polygon(ring.size());
  for (size_t i = 0; i < polygon.size(); ++i) {
    polygon[i] = static_cast<int>(i);
  }
  while (polygon.size() > 3) {
    size_t ear = 0;
    while (ear < polygon.size() && !isEar(points, polygon, ear)) {
      ++ear;
    }
    if (ear == polygon.size()) {
      return {};  // no ear: self-intersecting or degenerate ring
    }
    const size_t n = polygon.size();
    triangles.push_back({polygon[(ear + n - 1) % n], polygon[ear], polygon[(ear + 1) % n]});
    polygon.erase(polygon.begin() + static_cast<std::ptrdiff_t>(ear));
  }
  triangles.push_back({polygon[0], polygon[1], polygon[2]});
  return triangles;
}

Eigen::Vector3d defaultSiteOrigin(const citymodel::CityModel& model) {
  Eigen::AlignedBox2d bounds;
  for (const auto& building : model.buildings) {
    for (const auto& face : building.faces) {
      for (const auto& vertex : face.rings.front()) {
        bounds.extend(vertex.head<2>());
      }
    }
  }
  if (bounds.isEmpty()) {
    throw std::invalid_argument("defaultSiteOrigin: the city model has no building vertices");
  }
  const Eigen::Vector2d centre = bounds.center();
  return {std::round(centre.x()), std::round(centre.y()), 0.0};
}

CityMesh buildCityMesh(const citymodel::CityModel& model, const Eigen::Vector3d& site_origin) {
  if (model.buildings.empty()) {
    throw std::invalid_argument("buildCityMesh: the city model has no buildings");
  }
  CityMesh city;
  city.site_origin = site_origin;
  std::vector<double> base_heights;
  for (const citymodel::Building& building : model.buildings) {
    double base_z = std::numeric_limits<double>::infinity();
    double top_z = -base_z;
    for (const citymodel::Face& face : building.faces) {
      for (const Eigen::Vector3d& vertex : face.rings.front()) {
        base_z = std::min(base_z, vertex.z() - site_origin.z());
        top_z = std::max(top_z, vertex.z() - site_origin.z());
      }
    }
    if (!std::isfinite(base_z)) {
      continue;
    }
    ++city.building_count;
    base_heights.push_back(base_z);
    const SurfaceTag wall{SurfaceKind::kWall, static_cast<uint32_t>(city.building_count),
                          static_cast<float>(base_z), static_cast<float>(top_z)};
    for (const citymodel::Face& face : building.faces) {
      if (face.kind == citymodel::SurfaceKind::kGround) {
        continue;
      }
      const std::vector<Eigen::Vector3d>& ring = face.rings.front();
      const auto triangles = triangulateRing(ring, citymodel::newellVector(ring));
      city.skipped_faces += triangles.empty();
      SurfaceTag tag = wall;
      tag.kind = sceneKind(face.kind);
      for (const auto& t : triangles) {
        city.mesh.addTriangle(ring[t[0]] - site_origin, ring[t[1]] - site_origin,
                              ring[t[2]] - site_origin, tag);
      }
    }
  }
  if (base_heights.empty()) {
    throw std::invalid_argument("buildCityMesh: no building has any vertex");
  }
  std::nth_element(base_heights.begin(), base_heights.begin() + base_heights.size() / 2,
                   base_heights.end());
  city.ground_z_m = base_heights[base_heights.size() / 2];
  return city;
}

citymodel::CityModel readCityModelFile(const std::string& path) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) {
    throw std::runtime_error(fmt::format("cannot open city model '{}'", path));
  }
  std::ostringstream text;
  text << stream.rdbuf();
  const citymodel::ReadOptions options{.lod = "",
                                       .invalid_objects = citymodel::InvalidObjectPolicy::kSkip};
  const bool lines = path.size() >= 6 && path.compare(path.size() - 6, 6, ".jsonl") == 0;
  return lines ? citymodel::readCityJsonLines(text.str(), path, options)
               : citymodel::readCityJson(text.str(), path, options);
}

}  // namespace lineloc
