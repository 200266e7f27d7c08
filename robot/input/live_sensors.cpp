#include "robot/input/live_sensors.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>

namespace lineloc {
namespace {

// How often a reading thread looks whether it is to stop.
constexpr int kReadTimeoutMs = 100;
constexpr std::string_view kGpsd = "gpsd";

struct GpsdAddress {
  std::string host = "localhost";
  std::string port = "2947";
};

// "gpsd" or "gpsd:HOST:PORT"; nullopt for anything else (a device or a file).
std::optional<GpsdAddress> gpsdAddress(const std::string& source) {
  if (source == kGpsd) {
    return GpsdAddress{};
  }
  if (!source.starts_with("gpsd:")) {
    return std::nullopt;
  }
  const std::string rest = source.substr(kGpsd.size() + 1);
  const size_t colon = rest.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == rest.size()) {
    throw std::runtime_error(
        fmt::format("gnss_source '{}': gpsd is named 'gpsd' or 'gpsd:HOST:PORT'", source));
  }
  return GpsdAddress{rest.substr(0, colon), rest.substr(colon + 1)};
}

int64_t& stampOf(LiveReading& reading) {
  return std::visit(
      [](auto& value) -> int64_t& {
        if constexpr (std::is_same_v<std::decay_t<decltype(value)>, LiveFrame>) {
          return value.captured.stamp_ns;
        } else {
          return value.stamp_ns;
        }
      },
      reading);
}

// The fix or velocity of a GNSS reading that holds one.
std::optional<LiveReading> liveReading(const GpsReading& reading) {
  if (const auto* fix = std::get_if<GpsFix>(&reading)) {
    return *fix;
  }
  if (const auto* velocity = std::get_if<GpsVelocity>(&reading)) {
    return *velocity;
  }
  return std::nullopt;
}

template <typename Opener>
auto openSource(const char* option, const std::string& source, Opener open) {
  try {
    return open();
  } catch (const std::exception& error) {
    throw std::runtime_error(fmt::format("{} '{}': {}", option, source, error.what()));
  }
}

}  // namespace

LiveSensors::LiveSensors(const LiveSensorConfig& config, const RobotTimeBase& time_base,
                         const std::string& site_crs, const Eigen::Vector3d& site_origin,
                         const GnssErrorModel& gnss_errors,
                         std::vector<std::unique_ptr<LiveSource>> sources)
    : time_base_(time_base) {
  if (!config.gnss_source.empty() && site_crs.empty()) {
    throw std::runtime_error(
        fmt::format("gnss_source '{}' needs the site's CRS and origin (site_crs, site_origin)",
                    config.gnss_source));
  }
  const std::optional<GpsdAddress> gpsd_address =
      config.gnss_source.empty() ? std::nullopt : gpsdAddress(config.gnss_source);
  const bool frames_from_sources = std::any_of(
      sources.begin(), sources.end(),
      [](const std::unique_ptr<LiveSource>& source) { return source->deliversFrames(); });
  if (!frames_from_sources) {
    threads_.emplace_back(&LiveSensors::readCamera, this,
                          std::make_unique<VideoCamera>(config.camera, time_base));
  }
  try {
    sources_ = std::move(sources);
    for (std::unique_ptr<LiveSource>& source : sources_) {
      threads_.emplace_back(&LiveSensors::readSource, this, std::ref(*source));
    }
    if (!config.imu_source.empty()) {
      auto imu = openSource("imu_source", config.imu_source, [&] {
        return std::make_unique<SensorLineReader>(config.imu_source, config.imu_baud);
      });
      threads_.emplace_back(&LiveSensors::readCsv<ImuSample>, this, std::move(imu),
                            &parseEurocImuLine, &LiveSensorCounts::imu_lines_dropped);
    }
    if (!config.compass_source.empty()) {
      auto compass = openSource("compass_source", config.compass_source, [&] {
        return std::make_unique<SensorLineReader>(config.compass_source, config.compass_baud);
      });
      threads_.emplace_back(&LiveSensors::readCsv<CompassReading>, this, std::move(compass),
                            &parseCompassLine, &LiveSensorCounts::compass_lines_dropped);
    }
    if (gpsd_address) {
      auto gpsd = openSource("gnss_source", config.gnss_source, [&] {
        return std::make_unique<GpsdClient>(gpsd_address->host, gpsd_address->port,
                                            SiteProjection(site_crs, site_origin), gnss_errors);
      });
      threads_.emplace_back(&LiveSensors::readGpsd, this, std::move(gpsd));
    } else if (!config.gnss_source.empty()) {
      auto nmea = openSource("gnss_source", config.gnss_source, [&] {
        return std::make_unique<SensorLineReader>(config.gnss_source, config.gnss_baud);
      });
      threads_.emplace_back(
          &LiveSensors::readNmea, this, std::move(nmea),
          std::make_unique<NmeaGpsDecoder>(SiteProjection(site_crs, site_origin), gnss_errors));
    }
  } catch (...) {
    stopThreads();
    throw;
  }
}

LiveSensors::~LiveSensors() {
  stopThreads();
}

void LiveSensors::stopThreads() {
  stop_ = true;
  for (std::thread& thread : threads_) {
    thread.join();
  }
  threads_.clear();
}

std::vector<LiveReading> LiveSensors::take(int64_t timeout_ns) {
  std::unique_lock lock(mutex_);
  arrived_.wait_for(lock, std::chrono::nanoseconds(timeout_ns),
                    [&] { return !readings_.empty() || camera_ended_; });
  std::vector<LiveReading> taken(std::make_move_iterator(readings_.begin()),
                                 std::make_move_iterator(readings_.end()));
  readings_.clear();
  waiting_frame_.reset();
  return taken;
}

LiveSensorCounts LiveSensors::counts() const {
  std::lock_guard lock(mutex_);
  LiveSensorCounts counts = counts_;
  for (const std::unique_ptr<LiveSource>& source : sources_) {
    counts.source_dropped += source->dropped();
  }
  return counts;
}

void LiveSensors::push(LiveReading reading) {
  {
    std::lock_guard lock(mutex_);
    if (std::holds_alternative<LiveFrame>(reading)) {
      ++counts_.frames;
      if (waiting_frame_) {
        readings_.erase(readings_.begin() + static_cast<std::ptrdiff_t>(*waiting_frame_));
        ++counts_.frames_dropped;
      }
      waiting_frame_ = readings_.size();
    } else if (std::holds_alternative<ImuSample>(reading)) {
      ++counts_.imu_samples;
    } else if (std::holds_alternative<CompassReading>(reading)) {
      ++counts_.compass_readings;
    } else if (std::holds_alternative<GpsFix>(reading)) {
      ++counts_.gnss_fixes;
    } else {
      ++counts_.gnss_velocities;
    }
    readings_.push_back(std::move(reading));
  }
  arrived_.notify_one();
}

void LiveSensors::pushMapped(std::vector<LiveReading> readings, DeviceClock& clock,
                             int64_t arrival_ns) {
  if (readings.empty()) {
    return;
  }
  clock.observe(stampOf(readings.back()), arrival_ns);
  for (LiveReading& reading : readings) {
    stampOf(reading) = clock.map(stampOf(reading), arrival_ns);
    if (auto* frame = std::get_if<LiveFrame>(&reading)) {
      frame->captured.arrival_ns = arrival_ns;
    }
    push(std::move(reading));
  }
}

void LiveSensors::readCamera(std::unique_ptr<VideoCamera> camera) {
  uint32_t sequence = 0;
  while (!stop_) {
    std::optional<CapturedFrame> frame = camera->read();
    if (!frame) {
      break;
    }
    push(LiveFrame{sequence++, std::move(*frame)});
  }
  camera_ended_ = true;
  arrived_.notify_one();
}

template <typename Record>
void LiveSensors::readCsv(std::unique_ptr<SensorLineReader> stream,
                          CsvLine<Record> (*parse)(std::string_view),
                          int64_t LiveSensorCounts::*dropped) {
  DeviceClock clock;
  while (!stop_ && !stream->ended()) {
    const std::vector<std::string> lines = stream->readLines(kReadTimeoutMs);
    const int64_t arrival_ns = time_base_.now();
    std::vector<LiveReading> records;
    for (const std::string& line : lines) {
      const CsvLine<Record> parsed = parse(line);
      if (parsed.kind == CsvLineKind::kRecord) {
        records.emplace_back(parsed.record);
      } else if (parsed.kind == CsvLineKind::kMalformed) {
        std::lock_guard lock(mutex_);
        ++(counts_.*dropped);
      }
    }
    pushMapped(std::move(records), clock, arrival_ns);
  }
}

void LiveSensors::readNmea(std::unique_ptr<SensorLineReader> stream,
                           std::unique_ptr<NmeaGpsDecoder> decoder) {
  DeviceClock clock;
  while (!stop_ && !stream->ended()) {
    const std::vector<std::string> lines = stream->readLines(kReadTimeoutMs);
    const int64_t arrival_ns = time_base_.now();
    std::vector<LiveReading> readings;
    for (const std::string& line : lines) {
      const NmeaCounters before = decoder->counters();
      if (std::optional<LiveReading> reading = liveReading(decoder->decode(line))) {
        readings.push_back(std::move(*reading));
        continue;
      }
      const NmeaCounters& after = decoder->counters();
      std::lock_guard lock(mutex_);
      counts_.gnss_dropped += (after.malformed - before.malformed) +
                              (after.bad_checksum - before.bad_checksum) +
                              (after.undated - before.undated);
    }
    pushMapped(std::move(readings), clock, arrival_ns);
  }
}

void LiveSensors::readSource(LiveSource& source) {
  DeviceClock clock;
  source.run(
      [&](std::vector<LiveReading> readings) {
        pushMapped(std::move(readings), clock, time_base_.now());
      },
      stop_);
}

void LiveSensors::readGpsd(std::unique_ptr<GpsdClient> gpsd) {
  DeviceClock clock;
  while (!stop_) {
    GpsdReports reports;
    try {
      reports = gpsd->read(kReadTimeoutMs);
    } catch (const std::exception& error) {
      spdlog::error("GNSS: {}; no more fixes", error.what());
      return;
    }
    std::vector<LiveReading> readings;
    for (const GpsReading& reading : reports.readings) {
      if (std::optional<LiveReading> live = liveReading(reading)) {
        readings.push_back(std::move(*live));
      }
    }
    pushMapped(std::move(readings), clock, time_base_.now());
    std::lock_guard lock(mutex_);
    counts_.gnss_dropped += reports.without_fix;
  }
}

}  // namespace lineloc
