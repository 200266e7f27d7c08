// Fuzz target: a Kalibr camchain.yaml or an EuRoC sensor.yaml read as a camera.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>

#include "common/camera/kalibr_camera.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream stream(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const std::optional<lineloc::KalibrCamera> camera =
        lineloc::parseKalibrCamera(stream, "fuzz.yaml");
    if (camera && !(camera->calibration.camera.fx > 0.0 && camera->calibration.camera.width > 0 &&
                    camera->calibration.distortion.size() >= 4 &&
                    camera->calibration.distortion.size() <= 8 &&
                    std::isfinite(camera->timeshift_cam_imu_s))) {
      __builtin_trap();
    }
  } catch (const std::runtime_error&) {
  }
  return 0;
}
