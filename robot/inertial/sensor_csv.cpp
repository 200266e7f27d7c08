#include "robot/inertial/sensor_csv.h"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <stdexcept>

namespace lineloc {
namespace {

constexpr size_t kImuFieldCount = 7;
constexpr size_t kCompassFieldCount = 2;
constexpr size_t kMaxFields = 8;

std::string_view trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) {
    text.remove_prefix(1);
  }
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r' ||
                           text.back() == '\n')) {
    text.remove_suffix(1);
  }
  return text;
}

// Splits on commas; false when there are more than kMaxFields fields.
bool splitFields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  size_t start = 0;
  while (fields.size() < kMaxFields) {
    const size_t comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma - start)));
    if (comma == std::string_view::npos) {
      return true;
    }
    start = comma + 1;
  }
  return false;
}

template <typename T>
bool parseNumber(std::string_view text, T& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return !text.empty() && error == std::errc() && end == text.data() + text.size();
}

template <typename T>
CsvLine<T> malformed(std::string error) {
  CsvLine<T> line;
  line.kind = CsvLineKind::kMalformed;
  line.error = std::move(error);
  return line;
}

// Common shape: skip comments and blanks, split, check the field count and the stamp.
template <typename T>
std::optional<CsvLine<T>> splitRecord(std::string_view line, size_t field_count,
                                      std::vector<std::string_view>& fields, int64_t& stamp_ns) {
  line = trim(line);
  if (line.empty() || line.front() == '#') {
    CsvLine<T> skipped;
    skipped.kind = CsvLineKind::kSkipped;
    return skipped;
  }
  if (!splitFields(line, fields) || fields.size() != field_count) {
    return malformed<T>(fmt::format("expected {} comma-separated fields", field_count));
  }
  if (!parseNumber(fields[0], stamp_ns) || stamp_ns < 0) {
    return malformed<T>("timestamp is not a non-negative integer of nanoseconds");
  }
  return std::nullopt;
}

template <typename T>
CsvFile<T> readCsv(const std::string& path, CsvLine<T> (*parse)(std::string_view)) {
  std::ifstream stream(path);
  if (!stream) {
    throw std::runtime_error(fmt::format("cannot open sensor file '{}'", path));
  }
  CsvFile<T> file;
  std::string text;
  for (int number = 1; std::getline(stream, text); ++number) {
    CsvLine<T> line = parse(text);
    if (line.kind == CsvLineKind::kRecord) {
      file.records.push_back(line.record);
    } else if (line.kind == CsvLineKind::kMalformed) {
      ++file.malformed_lines;
      if (file.errors.size() < kMaxReportedErrors) {
        file.errors.push_back(fmt::format("{}:{}: {}", path, number, line.error));
      }
    }
  }
  return file;
}

}  // namespace

CsvLine<ImuSample> parseEurocImuLine(std::string_view line) {
  std::vector<std::string_view> fields;
  CsvLine<ImuSample> result;
  if (auto early = splitRecord<ImuSample>(line, kImuFieldCount, fields, result.record.stamp_ns)) {
    return *early;
  }
  std::array<double, 6> values{};
  for (size_t i = 0; i < values.size(); ++i) {
    if (!parseNumber(fields[i + 1], values[i])) {
      return malformed<ImuSample>(fmt::format("field {} is not a number", i + 2));
    }
  }
  result.kind = CsvLineKind::kRecord;
  result.record.gyro_radps = Eigen::Vector3d(values[0], values[1], values[2]);
  result.record.accel_mps2 = Eigen::Vector3d(values[3], values[4], values[5]);
  return result;
}

CsvLine<CompassReading> parseCompassLine(std::string_view line) {
  std::vector<std::string_view> fields;
  CsvLine<CompassReading> result;
  if (auto early =
          splitRecord<CompassReading>(line, kCompassFieldCount, fields, result.record.stamp_ns)) {
    return *early;
  }
  double heading_rad = 0.0;
  if (!parseNumber(fields[1], heading_rad) || !std::isfinite(heading_rad)) {
    return malformed<CompassReading>("heading is not a finite number of radians");
  }
  result.kind = CsvLineKind::kRecord;
  result.record.magnetic_heading_rad = heading_rad;
  return result;
}

CsvFile<ImuSample> readEurocImuCsv(const std::string& path) {
  return readCsv<ImuSample>(path, &parseEurocImuLine);
}

CsvFile<CompassReading> readCompassCsv(const std::string& path) {
  return readCsv<CompassReading>(path, &parseCompassLine);
}

}  // namespace lineloc
