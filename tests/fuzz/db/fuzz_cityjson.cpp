// Fuzz target: CityJSON and CityJSON Lines readers, then line extraction on
// whatever they accept. Only ModelError may come out of a reader.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "db/citymodel/cityjson_reader.h"
#include "db/citymodel/line_extraction.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  using lineloc::citymodel::InvalidObjectPolicy;
  for (const bool lines : {false, true}) {
    try {
      const lineloc::citymodel::ReadOptions options{.lod = "",
                                                    .invalid_objects = InvalidObjectPolicy::kSkip};
      const auto model = lines ? lineloc::citymodel::readCityJsonLines(text, "fuzz", options)
                               : lineloc::citymodel::readCityJson(text, "fuzz", options);
      for (const auto& building : model.buildings) {
        lineloc::citymodel::extractLines(building.faces);
      }
    } catch (const lineloc::citymodel::ModelError&) {
    }
  }
  return 0;
}
