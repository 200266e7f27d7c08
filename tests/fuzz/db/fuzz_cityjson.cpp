// Fuzz target: CityJSON and CityJSON Lines readers, then what the loader
// does with whatever they accept: faces repaired (degenerate ones dropped,
// bent ones triangulated), lines extracted, the terrain indexed and its
// height asked for. Only ModelError may come out of a reader or a repair, and
// std::invalid_argument of a terrain whose extent overflows.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "common/geometry/terrain_surface.h"
#include "db/citymodel/cityjson_reader.h"
#include "db/citymodel/line_extraction.h"
#include "db/citymodel/polygon_geometry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  using lineloc::citymodel::InvalidObjectPolicy;
  for (const bool lines : {false, true}) {
    try {
      const lineloc::citymodel::ReadOptions options{.lod = "",
                                                    .invalid_objects = InvalidObjectPolicy::kSkip};
      const auto model = lines ? lineloc::citymodel::readCityJsonLines(text, "fuzz", options)
                               : lineloc::citymodel::readCityJson(text, "fuzz", options);
      lineloc::citymodel::SkippedObjects skipped;
      for (auto building : model.buildings) {
        try {
          lineloc::citymodel::dropDegenerateFaces(building, {}, "fuzz", skipped);
        } catch (const lineloc::citymodel::ModelError&) {
          continue;
        }
        lineloc::citymodel::triangulateNonPlanarFaces(building, {}, "fuzz", skipped);
        lineloc::citymodel::extractLines(building.faces);
      }
      try {
        const lineloc::TerrainSurface terrain({model.terrain.begin(), model.terrain.end()});
        for (const auto& triangle : model.terrain) {
          terrain.heightAt(((triangle[0] + triangle[1] + triangle[2]) / 3.0).head<2>());
        }
      } catch (const std::invalid_argument&) {
      }
    } catch (const lineloc::citymodel::ModelError&) {
    }
  }
  return 0;
}
