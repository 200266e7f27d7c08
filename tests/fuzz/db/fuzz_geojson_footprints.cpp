// Fuzz target: GeoJSON footprints and their extrusion, then line extraction.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "db/citymodel/footprint_reader.h"
#include "db/citymodel/line_extraction.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto model = lineloc::citymodel::readGeoJsonFootprints(
        text, "fuzz.geojson", {},
        {.lod = "", .invalid_objects = lineloc::citymodel::InvalidObjectPolicy::kSkip});
    for (const auto& building : model.buildings) {
      lineloc::citymodel::extractLines(building.faces);
    }
  } catch (const lineloc::citymodel::ModelError&) {
  }
  return 0;
}
