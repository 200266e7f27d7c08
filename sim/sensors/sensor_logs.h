// Writes a simulated drive's sensor logs in the layout of an EuRoC/ASL
// dataset, so the robot reads them as it reads a real one:
//   <folder>/imu0/data.csv        EuRoC IMU, 200 Hz
//   <folder>/gps0/data.nmea       NMEA 0183 GGA + RMC, 1 Hz
//   <folder>/compass0/data.csv    magnetic heading (degrees), 10 Hz
//   <folder>/groundtruth.tum      T_world_body at IMU rate (TUM format)
#pragma once

#include <cstdint>
#include <string>

#include "sim/sensors/sensor_synthesis.h"

namespace lineloc::sim {

struct SensorLogConfig {
  std::string folder;
  TrajectoryConfig trajectory;
  ImuModel imu;
  GpsModel gps;
  CompassModel compass;
  std::string crs = "UTM:31N";
  Eigen::Vector3d site_origin = Eigen::Vector3d(593000.0, 5763000.0, 0.0);
};

struct SensorLogSummary {
  size_t imu_samples = 0;
  size_t gps_fixes = 0;
  size_t gps_outage_fixes = 0;
  size_t compass_readings = 0;
  size_t disturbed_compass_readings = 0;
  double grid_bearing_of_true_north_rad = 0.0;
};

// Creates the folders; throws std::runtime_error naming what it cannot write
// and std::invalid_argument for an unknown CRS.
SensorLogSummary writeSensorLogs(const SensorLogConfig& config);

}  // namespace lineloc::sim
