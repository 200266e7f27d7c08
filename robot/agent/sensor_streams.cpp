#include "robot/agent/sensor_streams.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "robot/inertial/sensor_csv.h"

namespace fs = std::filesystem;

namespace lineloc {
namespace {

template <typename T>
void takeCsv(const CsvFile<T>& file, std::vector<T>& records, SensorStreams& streams) {
  records = file.records;
  streams.dropped_lines += file.malformed_lines;
  streams.drop_reasons.insert(streams.drop_reasons.end(), file.errors.begin(), file.errors.end());
}

// gps0/data.csv rows: "timestamp_ns,sentence"; the row's stamp is the fix time.
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
    const auto comma = line.find(',');
    int64_t stamp_ns = 0;
    try {
      stamp_ns = comma == std::string::npos ? -1 : std::stoll(line.substr(0, comma));
    } catch (const std::exception&) {
      stamp_ns = -1;
    }
    std::optional<GpsFix> fix;
    if (stamp_ns > 0) {
      fix = decoder.decode(std::string_view(line).substr(comma + 1), stamp_ns);
    }
    if (!fix) {
      ++streams.dropped_lines;
      if (streams.drop_reasons.size() < kMaxReportedErrors) {
        streams.drop_reasons.push_back(
            fmt::format("{}:{}: no usable GGA fix", csv.string(), line_number));
      }
      continue;
    }
    fix->stamp_ns = stamp_ns;
    streams.gps.push_back(*fix);
  }
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
  if (fs::is_regular_file(dataset / "imu0" / "data.csv")) {
    takeCsv(readEurocImuCsv((dataset / "imu0" / "data.csv").string()), streams.imu, streams);
  }
  if (fs::is_regular_file(dataset / "compass0" / "data.csv")) {
    takeCsv(readCompassCsv((dataset / "compass0" / "data.csv").string()), streams.compass,
            streams);
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
  std::stable_sort(streams.timeline.begin(), streams.timeline.end(),
                   [](const SensorEvent& a, const SensorEvent& b) { return a.stamp_ns < b.stamp_ns; });
  return streams;
}

}  // namespace lineloc
