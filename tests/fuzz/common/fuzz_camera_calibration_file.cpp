// Fuzz target: a camera calibration file in any format readCameraCalibration
// reads (OpenCV's YAML, JSON and XML, a Kalibr camchain, an EuRoC
// sensor.yaml). It reads a path, so each input is written to a file first.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "common/camera/camera_calibration.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path =
      (std::filesystem::temp_directory_path() /
       ("fuzz_camera_calibration_" + std::to_string(::getpid()) + ".yaml"))
          .string();
  {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const lineloc::CameraCalibration calibration = lineloc::readCameraCalibration(path);
    if (!(calibration.camera.fx > 0.0 && calibration.camera.fy > 0.0 &&
          calibration.camera.width > 0 && calibration.camera.height > 0)) {
      __builtin_trap();
    }
  } catch (const std::runtime_error&) {
  }
  std::filesystem::remove(path);
  return 0;
}
