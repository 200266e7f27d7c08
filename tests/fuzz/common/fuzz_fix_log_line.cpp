// Fuzz target: lines of the robot's fix log (common/trajectory/fix_log.h).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "common/trajectory/fix_log.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string line(reinterpret_cast<const char*>(data), size);
  try {
    const lineloc::LoggedFix fix = lineloc::parseFixLogLine(line, "fuzz");
    const bool legs_finite = std::isfinite(fix.front_end_ms) && std::isfinite(fix.to_backbone_ms) &&
                             std::isfinite(fix.backbone_ms) && std::isfinite(fix.back_ms);
    if (!fix.T_world_camera.pose.matrix().allFinite() ||
        !fix.T_world_camera.covariance.allFinite() || !legs_finite) {
      __builtin_trap();  // accepted a non-finite pose, covariance or latency leg
    }
  } catch (const std::runtime_error&) {
  } catch (const std::out_of_range&) {
    __builtin_trap();  // an unguarded conversion escaped as the wrong error
  }
  return 0;
}
