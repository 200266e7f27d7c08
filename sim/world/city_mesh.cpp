#include "sim/world/city_mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "common/config/option_values.h"
#include "common/geometry/polygon_triangulation.h"
#include "db/citymodel/cityjson_reader.h"

namespace lineloc {
namespace {

SurfaceKind sceneKind(citymodel::SurfaceKind kind) {
  return kind == citymodel::SurfaceKind::kRoof ? SurfaceKind::kRoof : SurfaceKind::kWall;
}

}  // namespace

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

Eigen::Vector3d siteOriginOf(const citymodel::CityModel& model,
                             const std::vector<double>& site_origin) {
  return pointOption(site_origin, "site_origin").value_or(defaultSiteOrigin(model));
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
      const auto triangles = triangulatePolygon(ring);
      city.skipped_faces += triangles.empty();
      SurfaceTag tag = wall;
      tag.kind = sceneKind(face.kind);
      CityWall rendered{tag.object_id, tag.base_z, tag.top_z, {}};
      for (const auto& t : triangles) {
        const std::array<Eigen::Vector3d, 3> corners = {
            ring[t[0]] - site_origin, ring[t[1]] - site_origin, ring[t[2]] - site_origin};
        city.mesh.addTriangle(corners[0], corners[1], corners[2], tag);
        rendered.triangles.push_back(corners);
      }
      if (tag.kind == SurfaceKind::kWall && !rendered.triangles.empty()) {
        city.walls.push_back(std::move(rendered));
      }
    }
  }
  if (base_heights.empty()) {
    throw std::invalid_argument("buildCityMesh: no building has any vertex");
  }
  std::nth_element(base_heights.begin(), base_heights.begin() + base_heights.size() / 2,
                   base_heights.end());
  city.ground_z_m = base_heights[base_heights.size() / 2];
  std::vector<TerrainSurface::Triangle> terrain;
  terrain.reserve(model.terrain.size());
  const SurfaceTag ground{SurfaceKind::kGround, kTerrainObjectId, 0.0f, 0.0f};
  for (const citymodel::TerrainTriangle& triangle : model.terrain) {
    terrain.push_back(
        {triangle[0] - site_origin, triangle[1] - site_origin, triangle[2] - site_origin});
    city.mesh.addTriangle(terrain.back()[0], terrain.back()[1], terrain.back()[2], ground);
  }
  city.terrain = TerrainSurface(std::move(terrain));
  city.ground_z_m = city.terrain.lowestHeight().value_or(city.ground_z_m);
  return city;
}

double groundHeightAt(const CityMesh& city, const Eigen::Vector2d& xy) {
  return city.terrain.heightAt(xy).value_or(city.ground_z_m);
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
