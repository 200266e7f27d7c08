// The occupancy map of a city model around its default site origin: the
// bundled Delft tile, or a model of ../shared/data; throws std::runtime_error
// naming the file when it is missing.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "sim/world/city_mesh.h"
#include "sim/world/occupancy_map.h"

namespace lineloc {

inline OccupancyMap cityMap(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) {
    throw std::runtime_error("city model missing: " + path.string());
  }
  const citymodel::CityModel model = readCityModelFile(path.string());
  return OccupancyMap(buildCityMesh(model, defaultSiteOrigin(model)).mesh);
}

inline OccupancyMap bundledDelftMap() {
  return cityMap(std::filesystem::path(LINELOC_SOURCE_DIR) / "data" / "citymodels" / "delft.json");
}

inline OccupancyMap sharedCityMap(const std::string& file_name) {
  return cityMap(std::filesystem::path(LINELOC_SHARED_DATA_DIR) / "citymodels" / file_name);
}

}  // namespace lineloc
