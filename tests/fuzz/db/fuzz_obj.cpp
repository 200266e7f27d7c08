// Fuzz target: the Wavefront OBJ reader, then line extraction on what it accepts.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "db/citymodel/line_extraction.h"
#include "db/citymodel/obj_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto model = lineloc::citymodel::readWavefrontObj(
        text, "fuzz.obj", Eigen::Vector3d::Zero(),
        {.lod = "", .invalid_objects = lineloc::citymodel::InvalidObjectPolicy::kSkip});
    for (const auto& building : model.buildings) {
      lineloc::citymodel::extractLines(building.faces);
    }
  } catch (const lineloc::citymodel::ModelError&) {
  }
  return 0;
}
