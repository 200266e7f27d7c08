// The occupancy map of a city model in the shared data folder, around its
// default site origin; throws std::runtime_error naming the file when it is
// missing.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "sim/world/city_mesh.h"
#include "sim/world/occupancy_map.h"

namespace lineloc {

inline OccupancyMap sharedCityMap(const std::string& file_name) {
  const std::filesystem::path path =
      std::filesystem::path(LINELOC_SHARED_DATA_DIR) / "citymodels" / file_name;
  if (!std::filesystem::exists(path)) {
    throw std::runtime_error("shared data missing: " + path.string() +
                             " (set LINELOC_SHARED_DATA_DIR)");
  }
  const citymodel::CityModel model = readCityModelFile(path.string());
  return OccupancyMap(buildCityMesh(model, defaultSiteOrigin(model)).mesh);
}

}  // namespace lineloc
