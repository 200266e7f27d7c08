// Fuzz target: the T_BS block of EuRoC/ASL sensor.yaml files.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>

#include "robot/input/euroc_sensor.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream stream(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const Eigen::Isometry3d T_body_sensor = lineloc::parseEurocSensorPose(stream, "fuzz.yaml");
    if (!T_body_sensor.matrix().allFinite()) {
      __builtin_trap();
    }
  } catch (const std::runtime_error&) {
  }
  return 0;
}
