// Readers of the sensor logs a robot (or the simulator) writes:
//  - EuRoC/ASL imu0/data.csv: "timestamp [ns], w_x, w_y, w_z [rad/s], a_x, a_y, a_z [m/s^2]"
//    in the IMU's own frame (see InertialNavigatorConfig::R_body_imu);
//  - compass0/data.csv: "timestamp [ns], magnetic heading [rad]" clockwise from
//    magnetic north (SI units, like the rest of the EuRoC layout).
// Lines starting with '#' and blank lines are skipped; CR LF endings accepted.
// Numbers that parse but are not finite ("nan") are passed on: the navigator
// drops and counts them with the other bad samples.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "robot/inertial/imu_sample.h"
#include "robot/inertial/inertial_navigator.h"

namespace lineloc {

enum class CsvLineKind { kRecord, kSkipped, kMalformed };

template <typename T>
struct CsvLine {
  CsvLineKind kind = CsvLineKind::kMalformed;
  T record{};
  std::string error;  // why a malformed line is malformed
};

CsvLine<ImuSample> parseEurocImuLine(std::string_view line);
CsvLine<CompassReading> parseCompassLine(std::string_view line);

template <typename T>
struct CsvFile {
  std::vector<T> records;
  int malformed_lines = 0;
  std::vector<std::string> errors;  // "path:line: why", the first kMaxReportedErrors
};

inline constexpr size_t kMaxReportedErrors = 20;

// Read whole files; malformed lines are dropped and reported. Throws
// std::runtime_error naming the path when it cannot be opened.
CsvFile<ImuSample> readEurocImuCsv(const std::string& path);
CsvFile<CompassReading> readCompassCsv(const std::string& path);

}  // namespace lineloc
