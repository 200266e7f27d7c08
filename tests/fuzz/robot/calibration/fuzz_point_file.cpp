// Fuzz target: lineloc-calibrate's point files. Any input either parses into
// finite pairs or throws std::runtime_error.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

#include "robot/calibration/point_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    for (const Eigen::Vector2d& point : lineloc::parsePointPairs(text, "fuzz")) {
      if (!point.allFinite()) {
        std::abort();
      }
    }
  } catch (const std::runtime_error&) {
  }
  return 0;
}
