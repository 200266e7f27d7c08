// Fuzz target: the clutter box file parser must accept or reject any bytes
// with a std::runtime_error, never crash.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "sim/world/clutter_boxes.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    lineloc::parseClutterBoxes(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz");
  } catch (const std::runtime_error&) {
  }
  return 0;
}
