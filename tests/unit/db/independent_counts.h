// Test-side counts over the shared city-model files, computed straight from the
// JSON with nlohmann (not with lineloc's readers), to check what they load.
#pragma once

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace lineloc::test {

inline std::string sharedCityModelPath(const std::string& name) {
  const std::filesystem::path path =
      std::filesystem::path(LINELOC_SHARED_DATA_DIR) / "citymodels" / name;
  if (!std::filesystem::exists(path)) {
    throw std::runtime_error("shared data missing: " + path.string() +
                             " (configure LINELOC_SHARED_DATA_DIR)");
  }
  return path.string();
}

inline std::string readSharedCityModel(const std::string& name) {
  std::ifstream stream(sharedCityModelPath(name));
  std::stringstream contents;
  contents << stream.rdbuf();
  return contents.str();
}

struct CityModelCounts {
  int buildings = 0;  // Building and BuildingPart objects
  int faces = 0;      // surfaces of their geometry at the LoD
  // Of those, collapsed: a ring of fewer than 3 distinct vertices, or an
  // exterior ring of zero area (exact, in the quantised integer coordinates).
  int collapsed_faces = 0;
};

// Newell's area vector of a ring of integer vertices, exactly zero or not.
inline bool hasZeroArea(const nlohmann::json& ring, const nlohmann::json& vertices) {
  const auto at = [&](size_t i) {
    return vertices[ring[i % ring.size()].get<size_t>()].get<std::vector<int64_t>>();
  };
  const std::vector<int64_t> origin = at(0);
  int64_t sum[3] = {0, 0, 0};
  for (size_t i = 0; i < ring.size(); ++i) {
    std::vector<int64_t> a = at(i), b = at(i + 1);
    for (int k = 0; k < 3; ++k) {
      a[k] -= origin[k];
      b[k] -= origin[k];
    }
    sum[0] += a[1] * b[2] - a[2] * b[1];
    sum[1] += a[2] * b[0] - a[0] * b[2];
    sum[2] += a[0] * b[1] - a[1] * b[0];
  }
  return sum[0] == 0 && sum[1] == 0 && sum[2] == 0;
}

// In the shared files every Building/BuildingPart has geometry at the chosen
// LoD or BuildingPart children, so all of them are loaded. Surfaces are found
// by the nesting depth of the geometry type (MultiSurface 1, Solid 2 levels).
inline void countObjects(const nlohmann::json& objects, const nlohmann::json& vertices,
                         const std::string& lod, CityModelCounts& counts) {
  for (const auto& [id, object] : objects.items()) {
    const std::string type = object["type"];
    if (type != "Building" && type != "BuildingPart")
      continue;
    ++counts.buildings;
    for (const nlohmann::json& geometry : object.value("geometry", nlohmann::json::array())) {
      const nlohmann::json& geometry_lod = geometry["lod"];
      if ((geometry_lod.is_string() ? geometry_lod.get<std::string>() : geometry_lod.dump()) != lod)
        continue;
      const int depth =
          geometry["type"] == "MultiSurface" ? 0 : (geometry["type"] == "Solid" ? 1 : 2);
      std::vector<const nlohmann::json*> level = {&geometry["boundaries"]};
      for (int d = 0; d < depth; ++d) {
        std::vector<const nlohmann::json*> next;
        for (const nlohmann::json* node : level)
          for (const nlohmann::json& child : *node)
            next.push_back(&child);
        level = next;
      }
      for (const nlohmann::json* surfaces : level) {
        for (const nlohmann::json& surface : *surfaces) {
          bool collapsed = hasZeroArea(surface[0], vertices);
          for (const nlohmann::json& ring : surface) {
            std::set<std::vector<int64_t>> distinct;
            for (const nlohmann::json& index : ring)
              distinct.insert(vertices[index.get<size_t>()].get<std::vector<int64_t>>());
            collapsed |= distinct.size() < 3;
          }
          ++counts.faces;
          counts.collapsed_faces += collapsed ? 1 : 0;
        }
      }
    }
  }
}

// `name` is a CityJSON (.json) or CityJSON Lines (.jsonl) file of the shared data.
inline CityModelCounts countCityModel(const std::string& name, const std::string& lod) {
  const std::string text = readSharedCityModel(name);
  CityModelCounts counts;
  if (name.ends_with(".jsonl")) {
    std::istringstream lines(text);
    std::string line;
    std::getline(lines, line);  // the metadata header
    while (std::getline(lines, line)) {
      if (line.empty())
        continue;
      const nlohmann::json feature = nlohmann::json::parse(line);
      countObjects(feature["CityObjects"], feature["vertices"], lod, counts);
    }
  } else {
    const nlohmann::json document = nlohmann::json::parse(text);
    countObjects(document["CityObjects"], document["vertices"], lod, counts);
  }
  return counts;
}

}  // namespace lineloc::test
