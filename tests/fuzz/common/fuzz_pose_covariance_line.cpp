// Fuzz target: lines of the pose log with covariance
// (common/trajectory/pose_covariance_log.h).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "common/trajectory/pose_covariance_log.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string line(reinterpret_cast<const char*>(data), size);
  try {
    const lineloc::StampedPoseWithCovariance stamped =
        lineloc::parsePoseCovarianceLine(line, "fuzz");
    if (!stamped.pose.pose.matrix().allFinite() || !stamped.pose.covariance.allFinite()) {
      __builtin_trap();  // accepted a non-finite pose or covariance
    }
  } catch (const std::runtime_error&) {
  } catch (const std::out_of_range&) {
    __builtin_trap();  // an unguarded conversion escaped as the wrong error
  }
  return 0;
}
