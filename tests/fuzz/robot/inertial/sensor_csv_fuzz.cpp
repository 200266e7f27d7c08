// Feeds arbitrary bytes, line by line, to the EuRoC IMU and compass CSV
// parsers and the navigator: whatever parses must be safe to add.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "robot/inertial/inertial_navigator.h"
#include "robot/inertial/sensor_csv.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  lineloc::InertialNavigator navigator(lineloc::InertialNavigatorConfig{});
  while (!text.empty()) {
    const size_t end = text.find('\n');
    const std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
    const auto imu = lineloc::parseEurocImuLine(line);
    if (imu.kind == lineloc::CsvLineKind::kRecord) {
      navigator.addImu(imu.record);
    } else if (imu.kind == lineloc::CsvLineKind::kMalformed && imu.error.empty()) {
      std::abort();
    }
    const auto compass = lineloc::parseCompassLine(line);
    if (compass.kind == lineloc::CsvLineKind::kRecord) {
      navigator.addCompass(compass.record);
    }
  }
  return 0;
}
