// lineloc-sim-sensors: writes a simulated ground robot's IMU, DGPS (NMEA) and
// compass logs and its ground truth, in the EuRoC/ASL dataset layout.
#include <spdlog/spdlog.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "common/config/program_options.h"
#include "sim/sensors/sensor_logs.h"

int main(int argc, char** argv) {
  lineloc::sim::SensorLogConfig config;
  config.folder = "sim_sensors";
  double magnetic_declination_deg = 0.0;
  double compass_sigma_deg = config.compass.sigma_rad * 180.0 / M_PI;
  std::vector<double> site_origin = {config.site_origin.x(), config.site_origin.y(),
                                     config.site_origin.z()};
  lineloc::ProgramOptions options("lineloc-sim-sensors",
                                  "simulated IMU, DGPS and compass logs of a ground robot");
  options.add("out", config.folder, "dataset folder to write (created)");
  options.add("seed", config.trajectory.seed, "random seed: same seed, same files");
  options.add("duration_s", config.trajectory.duration_s, "length of the drive (s)");
  options.add("initial_still_s", config.trajectory.initial_still_s,
              "standing still at the start, for the IMU alignment (s)");
  options.add("max_speed_m_s", config.trajectory.max_speed_mps, "highest driving speed (m/s)");
  options.add("imu_rate_hz", config.imu.rate_hz, "IMU sample rate (Hz)");
  options.add("imu_noise", config.imu.noise, "false: exact IMU samples, zero biases");
  options.add("gps_outage_probability", config.gps.outage_probability,
              "probability per DGPS fix that an outage starts");
  options.add("compass_sigma_deg", compass_sigma_deg, "compass white noise (degrees)");
  options.add("magnetic_declination_deg", magnetic_declination_deg,
              "magnetic declination at the site, east positive (degrees)");
  options.add("site_crs", config.crs, "CRS of the site frame: UTM:<zone><N|S> or EPSG:<code>");
  options.addFixedSize("site_origin", site_origin, 3, "site origin x y z in that CRS (m)");
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  config.compass.sigma_rad = compass_sigma_deg * M_PI / 180.0;
  config.compass.magnetic_declination_rad = magnetic_declination_deg * M_PI / 180.0;
  config.site_origin = Eigen::Vector3d(site_origin[0], site_origin[1], site_origin[2]);
  try {
    const auto summary = lineloc::sim::writeSensorLogs(config);
    std::cout << fmt::format(
        "lineloc-sim-sensors: {} IMU samples, {} DGPS fixes ({} in outages), {} compass "
        "readings ({} disturbed) in {}\n",
        summary.imu_samples, summary.gps_fixes, summary.gps_outage_fixes, summary.compass_readings,
        summary.disturbed_compass_readings, config.folder);
    return 0;
  } catch (const std::exception& error) {
    spdlog::error("{}", error.what());
    return 1;
  }
}
