// The simulator's files work as they are: lineloc-sim-sensors' logs, read back
// with the robot's readers, start the navigator (compass + DGPS) and, with
// vision fixes from the ground truth, it tracks.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "common/trajectory/tum_trajectory.h"
#include "robot/inertial/nmea_gps_decoder.h"
#include "robot/inertial/sensor_csv.h"
#include "sim/sensors/sensor_logs.h"

namespace lineloc {
namespace {

TEST(SimulatedLogs, NavigatorStartsAndTracksFromTheFiles) {
  sim::SensorLogConfig logs;
  logs.folder =
      (std::filesystem::temp_directory_path() / ("lineloc_sim_logs_" + std::to_string(::getpid())))
          .string();
  logs.trajectory.seed = 31;
  logs.trajectory.duration_s = 60.0;
  logs.trajectory.start_yaw_rad = -2.0;
  logs.gps.outage_probability = 0.05;
  logs.compass.magnetic_declination_rad = 0.035;
  const sim::SensorLogSummary summary = sim::writeSensorLogs(logs);

  const auto imu = readEurocImuCsv(logs.folder + "/imu0/data.csv");
  const auto compass = readCompassCsv(logs.folder + "/compass0/data.csv");
  const auto truth = readTumFile(logs.folder + "/groundtruth.tum");
  EXPECT_EQ(imu.malformed_lines, 0);
  EXPECT_EQ(compass.malformed_lines, 0);
  ASSERT_EQ(imu.records.size(), summary.imu_samples);
  ASSERT_EQ(truth.size(), summary.imu_samples);
  NmeaGpsDecoder decoder(SiteProjection(logs.crs, logs.site_origin));
  std::vector<GpsFix> gps;
  std::ifstream nmea(logs.folder + "/gps0/data.nmea");
  for (std::string line; std::getline(nmea, line);) {
    const GpsReading reading = decoder.decode(line);
    if (const auto* fix = std::get_if<GpsFix>(&reading)) {
      gps.push_back(*fix);
    }
  }
  // Each epoch is GGA then RMC: the first GGA comes before any date.
  const NmeaCounters& counters = decoder.counters();
  EXPECT_EQ(counters.undated, 1);
  EXPECT_EQ(counters.fixes + counters.no_fix / 2 + counters.undated,
            static_cast<int64_t>(summary.gps_fixes));
  EXPECT_EQ(decoder.counters().no_fix, 2 * static_cast<int64_t>(summary.gps_outage_fixes));
  // Every RMC with a fix carries a speed and a course.
  EXPECT_EQ(counters.velocities,
            static_cast<int64_t>(summary.gps_fixes - summary.gps_outage_fixes));
  std::filesystem::remove_all(logs.folder);

  InertialNavigatorConfig config;
  config.magnetic_declination_rad = logs.compass.magnetic_declination_rad;
  config.grid_bearing_of_true_north_rad = summary.grid_bearing_of_true_north_rad;
  InertialNavigator navigator(config);
  std::mt19937_64 random(3);
  std::normal_distribution<double> noise(0.0, 0.03);
  size_t next_gps = 0;
  size_t next_compass = 0;
  for (size_t i = 0; i < imu.records.size(); ++i) {
    const int64_t now = imu.records[i].stamp_ns;
    for (; next_gps < gps.size() && gps[next_gps].stamp_ns <= now; ++next_gps) {
      navigator.addGps(gps[next_gps]);
    }
    for (; next_compass < compass.records.size() && compass.records[next_compass].stamp_ns <= now;
         ++next_compass) {
      navigator.addCompass(compass.records[next_compass]);
    }
    // 10 Hz vision fixes from 20 s on, 100 ms late, 3 cm noise.
    if (i >= 4020 && i % 20 == 0) {
      const StampedPose& frame = truth[i - 20];
      PoseWithCovariance fix;
      fix.pose = frame.pose * config.T_body_camera;
      fix.pose.translation() += Eigen::Vector3d(noise(random), noise(random), noise(random));
      fix.covariance = diagonalPoseCovariance(0.03, 0.002);
      navigator.applyVisionFix(frame.stamp_ns, fix);
    }
    navigator.addImu(imu.records[i]);
    // At 4 s, still standing: aligned (2 s window) and started from compass and
    // DGPS, unless the simulated DGPS was in an outage until then.
    if (i == 800 && !gps.empty() && gps.front().stamp_ns <= now) {
      EXPECT_TRUE(navigator.state().has_value());
      EXPECT_EQ(navigator.health().mode, NavigatorMode::kDeadReckoning);
    }
  }
  const auto estimate = navigator.state();
  ASSERT_TRUE(estimate.has_value());
  // TUM keeps micrometres and 1e-9 of the quaternion.
  EXPECT_LT((estimate->state.p_world_body - truth.back().pose.translation()).norm(), 0.1);
  EXPECT_EQ(navigator.health().mode, NavigatorMode::kTracking);
}

}  // namespace
}  // namespace lineloc
