// Fuzz target: EuRoC/ASL camera data.csv files.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>

#include "robot/input/image_sequence.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream stream(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const auto frames = lineloc::parseEurocCameraCsv(stream, "fuzz.csv", "data");
    for (size_t i = 1; i < frames.size(); ++i) {
      if (*frames[i].stamp_ns <= *frames[i - 1].stamp_ns) {
        __builtin_trap();
      }
    }
  } catch (const std::runtime_error&) {
  }
  return 0;
}
