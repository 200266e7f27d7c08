#include "backbone/map/ground_level.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace lineloc {
namespace {

std::optional<double> buildingFeetMedian(const MapView& view) {
  std::map<int64_t, double> lowest_by_building;
  for (const db::ModelFaceRecord& face : view.faces) {
    const auto entry =
        lowest_by_building.try_emplace(face.building_id, std::numeric_limits<double>::infinity())
            .first;
    for (const Eigen::Vector3d& vertex : face.ring_world) {
      entry->second = std::min(entry->second, vertex.z());
    }
  }
  std::vector<double> lowest;
  for (const auto& [building, z] : lowest_by_building) {
    if (std::isfinite(z)) {
      lowest.push_back(z);
    }
  }
  if (lowest.empty()) {
    return std::nullopt;
  }
  const auto median = lowest.begin() + static_cast<std::ptrdiff_t>(lowest.size() / 2);
  std::nth_element(lowest.begin(), median, lowest.end());
  return *median;
}

std::vector<TerrainSurface::Triangle> terrainTriangles(const MapView& view) {
  std::vector<TerrainSurface::Triangle> triangles;
  triangles.reserve(view.terrain.size());
  for (const db::TerrainTriangleRecord& triangle : view.terrain) {
    triangles.push_back(triangle.corners_world);
  }
  return triangles;
}

}  // namespace

GroundLevel::GroundLevel(const MapView& view)
    : terrain_(terrainTriangles(view)), building_feet_median_(buildingFeetMedian(view)) {}

std::optional<double> GroundLevel::at(const Eigen::Vector2d& position_world) const {
  if (const std::optional<double> height = terrain_.heightAt(position_world)) {
    return height;
  }
  return building_feet_median_;
}

}  // namespace lineloc
