#include "robot/agent/sensor_streams.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "robot/inertial/sensor_csv.h"
#include "robot/input/euroc_sensor.h"

namespace fs = std::filesystem;

namespace lineloc {
namespace {

template <typename T>
void takeCsv(const CsvFile<T>& file, std::vector<T>& records, SensorStreams& streams) {
  records = file.records;
  streams.dropped_lines += file.malformed_lines;
  streams.drop_reasons.insert(streams.drop_reasons.end(), file.errors.begin(), file.errors.end());
}

// The NMEA sentence of a gps0/data.csv row, without the CSV quotes around it.
std::string_view csvSentence(std::string_view field) {
  if (field.size() >= 2 && field.front() == '"' && field.back() == '"') {
    return field.substr(1, field.size() - 2);
  }
  return field;
}

int64_t rowStampNs(const std::string& line, size_t comma) {
  if (comma == std::string::npos)
    return -1;
  try {
    return std::stoll(line.substr(0, comma));
  } catch (const std::exception&) {
    return -1;
  }
}

// gps0/data.csv rows: "timestamp_ns,sentence"; the row's stamp is the fix
// time. RMC rows and GGA rows without a fix are valid input that gives no
// position; only rows the decoder finds malformed are dropped and reported.
void readGps(const fs::path& csv, NmeaGpsDecoder& decoder, SensorStreams& streams) {
  std::ifstream stream(csv);
  if (!stream) {
    throw std::runtime_error(fmt::format("cannot open '{}'", csv.string()));
  }
  std::string line;
  for (int line_number = 1; std::getline(stream, line); ++line_number) {
    if (line.empty() || line[0] == '#') {
      continue;
    }
    const size_t comma = line.find(',');
    const int64_t stamp_ns = rowStampNs(line, comma);
    const NmeaCounters before = decoder.counters();
    std::optional<GpsFix> fix;
    if (stamp_ns > 0) {
      fix = decoder.decode(csvSentence(std::string_view(line).substr(comma + 1)), stamp_ns);
    }
    if (fix) {
      fix->stamp_ns = stamp_ns;
      streams.gps.push_back(*fix);
      continue;
    }
    const NmeaCounters& after = decoder.counters();
    const bool malformed = stamp_ns <= 0 || after.malformed != before.malformed ||
                           after.bad_checksum != before.bad_checksum;
    if (!malformed) {
      continue;
    }
    ++streams.dropped_lines;
    if (streams.drop_reasons.size() < kMaxReportedErrors) {
      streams.drop_reasons.push_back(fmt::format(
          "{}:{}: malformed DGPS row (time stamp or NMEA sentence)", csv.string(), line_number));
    }
  }
}

std::optional<Eigen::Isometry3d> sensorPose(const fs::path& sensor_yaml) {
  if (!fs::is_regular_file(sensor_yaml))
    return std::nullopt;
  return readEurocSensorPose(sensor_yaml.string());
}

template <typename T>
void addEvents(const std::vector<T>& records, SensorKind kind, SensorStreams& streams) {
  for (size_t i = 0; i < records.size(); ++i) {
    streams.timeline.push_back({records[i].stamp_ns, kind, i});
  }
}

}  // namespace

SensorStreams loadSensorStreams(const std::string& root, NmeaGpsDecoder* gps) {
  SensorStreams streams;
  streams.frames = listImageSequence(root);
  const fs::path dataset(root);
  streams.T_body_camera = sensorPose(dataset / "cam0" / "sensor.yaml");
  streams.T_body_imu = sensorPose(dataset / "imu0" / "sensor.yaml");
  if (fs::is_regular_file(dataset / "imu0" / "data.csv")) {
    takeCsv(readEurocImuCsv((dataset / "imu0" / "data.csv").string()), streams.imu, streams);
  }
  if (fs::is_regular_file(dataset / "compass0" / "data.csv")) {
    takeCsv(readCompassCsv((dataset / "compass0" / "data.csv").string()), streams.compass, streams);
  }
  if (gps != nullptr && fs::is_regular_file(dataset / "gps0" / "data.csv")) {
    readGps(dataset / "gps0" / "data.csv", *gps, streams);
  }
  const bool timed = !streams.imu.empty() || !streams.gps.empty() || !streams.compass.empty();
  for (size_t i = 0; i < streams.frames.size(); ++i) {
    if (timed && !streams.frames[i].stamp_ns) {
      throw std::runtime_error(fmt::format(
          "frame '{}' has no time stamp, so it cannot be replayed with the other sensors",
          streams.frames[i].path));
    }
    streams.timeline.push_back({streams.frames[i].stamp_ns.value_or(0), SensorKind::kFrame, i});
  }
  addEvents(streams.imu, SensorKind::kImu, streams);
  addEvents(streams.gps, SensorKind::kGps, streams);
  addEvents(streams.compass, SensorKind::kCompass, streams);
  std::stable_sort(
      streams.timeline.begin(), streams.timeline.end(),
      [](const SensorEvent& a, const SensorEvent& b) { return a.stamp_ns < b.stamp_ns; });
  return streams;
}

}  // namespace lineloc
