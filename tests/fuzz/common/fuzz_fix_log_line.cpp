// Fuzz target: lines of the robot's fix log (common/trajectory/fix_log.h).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "common/trajectory/fix_log.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string line(reinterpret_cast<const char*>(data), size);
  try {
    const lineloc::LoggedFix fix = lineloc::parseFixLogLine(line, "fuzz");
    if (!fix.T_world_camera.pose.matrix().allFinite() ||
        !fix.T_world_camera.covariance.allFinite()) {
      __builtin_trap();  // accepted a non-finite pose or covariance
    }
  } catch (const std::runtime_error&) {
  } catch (const std::out_of_range&) {
    __builtin_trap();  // an unguarded conversion escaped as the wrong error
  }
  return 0;
}
