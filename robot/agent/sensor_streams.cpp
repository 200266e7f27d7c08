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
// time. GGA rows give positions, RMC rows velocities; GGA rows without a fix,
// and RMC rows without one or without speed and course, are valid input that
// gives neither; only rows the decoder finds malformed are dropped and reported.
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
    GpsReading reading;
    if (stamp_ns > 0) {
      reading = decoder.decode(csvSentence(std::string_view(line).substr(comma + 1)), stamp_ns);
    }
    if (auto* fix = std::get_if<GpsFix>(&reading)) {
      fix->stamp_ns = stamp_ns;
      streams.gps.push_back(*fix);
      continue;
    }
    if (auto* velocity = std::get_if<GpsVelocity>(&reading)) {
      velocity->stamp_ns = stamp_ns;
      streams.gps_velocity.push_back(*velocity);
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

std::optional<ImuNoiseDensities> imuNoise(const fs::path& sensor_yaml) {
  if (!fs::is_regular_file(sensor_yaml)) {
    return std::nullopt;
  }
  return readEurocImuNoise(sensor_yaml.string());
}

template <typename T>
int64_t stampOf(const T& record) {
  return record.stamp_ns;
}

int64_t stampOf(const FrameRef& frame) {
  return frame.stamp_ns.value_or(0);
}

template <typename T>
void eraseBefore(int64_t stamp_ns, std::vector<T>& records) {
  std::erase_if(records, [&](const T& record) { return stampOf(record) < stamp_ns; });
}

template <typename T>
void takeEarliest(const std::vector<T>& records, int64_t& first_ns) {
  if (!records.empty()) {
    first_ns = std::min(first_ns, stampOf(records.front()));
  }
}

// Leaves out every record of the first `offset_ns` of the streams.
void startAfter(int64_t offset_ns, SensorStreams& streams) {
  if (offset_ns <= 0) {
    return;
  }
  if (streams.frames.empty() || !streams.frames.front().stamp_ns) {
    throw std::runtime_error("a replay that starts later needs time-stamped frames");
  }
  int64_t first_ns = stampOf(streams.frames.front());
  takeEarliest(streams.imu, first_ns);
  takeEarliest(streams.gps, first_ns);
  takeEarliest(streams.gps_velocity, first_ns);
  takeEarliest(streams.compass, first_ns);
  const int64_t start_ns = first_ns + offset_ns;
  eraseBefore(start_ns, streams.frames);
  eraseBefore(start_ns, streams.imu);
  eraseBefore(start_ns, streams.gps);
  eraseBefore(start_ns, streams.gps_velocity);
  eraseBefore(start_ns, streams.compass);
}

template <typename T>
void addEvents(const std::vector<T>& records, SensorKind kind, SensorStreams& streams) {
  for (size_t i = 0; i < records.size(); ++i) {
    streams.timeline.push_back({records[i].stamp_ns, kind, i});
  }
}

}  // namespace

void requireNavigationSensors(const std::string& root, const SensorStreams& streams,
                              bool gps_decoded, bool start_pose_given) {
  const fs::path dataset(root);
  if (!fs::is_directory(dataset / "cam0")) {
    return;
  }
  const fs::path imu = dataset / "imu0" / "data.csv";
  if (!fs::is_regular_file(imu)) {
    throw std::runtime_error(fmt::format(
        "dataset '{}' has no IMU stream: '{}' is missing, and without it the robot cannot keep "
        "its pose between fixes",
        root, imu.string()));
  }
  if (streams.imu.empty()) {
    throw std::runtime_error(fmt::format("'{}' holds no valid IMU sample", imu.string()));
  }
  const fs::path gps = dataset / "gps0" / "data.csv";
  if (start_pose_given) {
    return;
  }
  if (!fs::is_regular_file(gps)) {
    throw std::runtime_error(fmt::format(
        "dataset '{}' has no DGPS stream: '{}' is missing, and without a first position (or a "
        "start pose) the robot never localises",
        root, gps.string()));
  }
  if (!gps_decoded) {
    throw std::runtime_error(fmt::format(
        "'{}' needs the site's CRS and origin (site_crs, site_origin) to be read: without a "
        "first position the robot never localises",
        gps.string()));
  }
  if (streams.gps.empty()) {
    throw std::runtime_error(fmt::format("'{}' holds no valid DGPS position", gps.string()));
  }
}

SensorStreams loadSensorStreams(const std::string& root, NmeaGpsDecoder* gps,
                                const StreamTiming& timing) {
  SensorStreams streams;
  streams.frames = listImageSequence(root);
  for (FrameRef& frame : streams.frames) {
    if (frame.stamp_ns) {
      *frame.stamp_ns -= timing.camera_time_offset_ns;
    }
  }
  const fs::path dataset(root);
  streams.T_body_camera = sensorPose(dataset / "cam0" / "sensor.yaml");
  streams.T_body_imu = sensorPose(dataset / "imu0" / "sensor.yaml");
  streams.imu_noise = imuNoise(dataset / "imu0" / "sensor.yaml");
  if (fs::is_regular_file(dataset / "imu0" / "data.csv")) {
    takeCsv(readEurocImuCsv((dataset / "imu0" / "data.csv").string()), streams.imu, streams);
  }
  if (fs::is_regular_file(dataset / "compass0" / "data.csv")) {
    takeCsv(readCompassCsv((dataset / "compass0" / "data.csv").string()), streams.compass, streams);
  }
  if (gps != nullptr && fs::is_regular_file(dataset / "gps0" / "data.csv")) {
    readGps(dataset / "gps0" / "data.csv", *gps, streams);
  }
  const bool timed = !streams.imu.empty() || !streams.gps.empty() ||
                     !streams.gps_velocity.empty() || !streams.compass.empty();
  for (size_t i = 0; i < streams.frames.size(); ++i) {
    if (timed && !streams.frames[i].stamp_ns) {
      throw std::runtime_error(fmt::format(
          "frame '{}' has no time stamp, so it cannot be replayed with the other sensors",
          streams.frames[i].path));
    }
  }
  startAfter(timing.start_offset_ns, streams);
  for (size_t i = 0; i < streams.frames.size(); ++i) {
    streams.timeline.push_back({stampOf(streams.frames[i]), SensorKind::kFrame, i});
  }
  addEvents(streams.imu, SensorKind::kImu, streams);
  addEvents(streams.gps, SensorKind::kGps, streams);
  addEvents(streams.gps_velocity, SensorKind::kGpsVelocity, streams);
  addEvents(streams.compass, SensorKind::kCompass, streams);
  std::stable_sort(
      streams.timeline.begin(), streams.timeline.end(),
      [](const SensorEvent& a, const SensorEvent& b) { return a.stamp_ns < b.stamp_ns; });
  return streams;
}

}  // namespace lineloc
