#include "sim/sensors/sensor_logs.h"

#include <fmt/format.h>

#include <filesystem>
#include <stdexcept>

#include "common/trajectory/tum_trajectory.h"

namespace lineloc::sim {
namespace {

// Independent random streams per sensor, all from the one trajectory seed.
constexpr uint64_t kImuStream = 1;
constexpr uint64_t kGpsStream = 2;
constexpr uint64_t kCompassStream = 3;

std::string makeFolder(const std::filesystem::path& folder) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) {
    throw std::runtime_error(
        fmt::format("cannot create folder '{}': {}", folder.string(), error.message()));
  }
  return folder.string();
}

}  // namespace

SensorLogSummary writeSensorLogs(const SensorLogConfig& config) {
  const std::filesystem::path root(config.folder);
  const SiteProjection projection(config.crs, config.site_origin);
  const GroundTruthTrajectory trajectory(config.trajectory);
  const uint64_t seed = config.trajectory.seed * 1000;
  SensorLogSummary summary;
  summary.grid_bearing_of_true_north_rad = projection.gridBearingOfTrueNorth_rad(
      projection.toGeodetic(config.trajectory.start_position_m));

  const auto imu = synthesiseImu(trajectory, config.imu, seed + kImuStream);
  writeEurocImuCsv(makeFolder(root / "imu0") + "/data.csv", imu);
  summary.imu_samples = imu.size();

  const auto gps = synthesiseGps(trajectory, config.gps, seed + kGpsStream);
  writeNmeaFile(makeFolder(root / "gps0") + "/data.nmea", gps, projection);
  summary.gps_fixes = gps.size();
  for (const SimGpsFix& fix : gps) {
    summary.gps_outage_fixes += fix.valid ? 0 : 1;
  }

  const auto compass = synthesiseCompass(
      trajectory, config.compass, summary.grid_bearing_of_true_north_rad, seed + kCompassStream);
  writeCompassCsv(makeFolder(root / "compass0") + "/data.csv", compass);
  summary.compass_readings = compass.size();
  for (const SimCompassReading& reading : compass) {
    summary.disturbed_compass_readings += reading.disturbed ? 1 : 0;
  }

  TumWriter truth((root / "groundtruth.tum").string());
  for (const SimImuSample& sample : imu) {
    const TruthSample state = trajectory.at(sample.stamp_ns);
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    T_world_body.linear() = state.q_world_body.toRotationMatrix();
    T_world_body.translation() = state.p_world_body;
    truth.write({sample.stamp_ns, T_world_body});
  }
  return summary;
}

}  // namespace lineloc::sim
