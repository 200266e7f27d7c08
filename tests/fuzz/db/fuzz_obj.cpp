// Fuzz target: the Wavefront OBJ reader, z-up and y-up, then line extraction
// on what it accepts.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "db/citymodel/line_extraction.h"
#include "db/citymodel/obj_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using lineloc::citymodel::UpAxis;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  for (const UpAxis up_axis : {UpAxis::kZ, UpAxis::kY}) {
    try {
      const auto model = lineloc::citymodel::readWavefrontObj(
          text, "fuzz.obj", Eigen::Vector3d::Zero(),
          {.lod = "",
           .invalid_objects = lineloc::citymodel::InvalidObjectPolicy::kSkip,
           .up_axis = up_axis});
      for (const auto& building : model.buildings) {
        lineloc::citymodel::extractLines(building.faces);
      }
    } catch (const lineloc::citymodel::ModelError&) {
    }
  }
  return 0;
}
