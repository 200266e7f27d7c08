// Fuzz target: TUM trajectory lines.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "common/trajectory/tum_trajectory.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string line(reinterpret_cast<const char*>(data), size);
  try {
    const lineloc::StampedPose pose = lineloc::parseTumLine(line, "fuzz");
    if (!pose.pose.matrix().allFinite()) {
      __builtin_trap();  // accepted a non-finite pose
    }
  } catch (const std::runtime_error&) {
  } catch (const std::out_of_range&) {
    __builtin_trap();  // an unguarded conversion escaped as the wrong error
  }
  return 0;
}
