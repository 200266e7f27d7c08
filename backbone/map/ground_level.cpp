#include "backbone/map/ground_level.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

namespace lineloc {

std::optional<double> groundLevel(const MapView& view) {
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

}  // namespace lineloc
