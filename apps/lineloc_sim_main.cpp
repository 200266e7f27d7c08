// lineloc-sim: renders a drive through a city model and writes it, with the
// synthesised IMU, DGPS and compass and the ground truth, as an EuRoC/ASL
// dataset folder.
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <iostream>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "common/config/program_options.h"
#include "common/progress/progress_meter.h"
#include "common/time/utc_time.h"
#include "sim/dataset/drive_simulation.h"

int main(int argc, char** argv) {
  lineloc::DriveSimulationConfig config;
  config.output = "sim_dataset";
  lineloc::ProgramOptions options("lineloc-sim",
                                  "simulated drive through a city model -> EuRoC/ASL dataset");
  options.add("city_model", config.city_model,
              "CityJSON (.json) or CityJSON Lines (.jsonl) file (required; lineloc bundles "
              "data/citymodels/delft.json)");
  options.add("city_model_crs", config.crs,
              "CRS of the city model, e.g. EPSG:7415 (empty: the one it names)");
  options.addFixedSize(
      "site_origin", config.site_origin, 3,
      "model coordinates x y z of the site origin (empty: centre of the buildings)");
  options.add("out", config.output, "dataset folder to create (must be empty or absent)");
  options.add("seed", config.seed, "seed of every random choice: same seed, same bytes");
  options.add("duration_s", config.duration_s, "length of the drive (s)");
  options.add("waypoints", config.waypoints,
              "route file of 'x y' lines in the site frame (empty: planned in the streets)");
  options.add("min_clearance_m", config.network.min_clearance_m,
              "streets of the planned route keep this far from façades (m)");
  options.add("max_facade_distance_m", config.network.max_facade_distance_m,
              "a street has façades on both sides within this distance; beyond is open land (m)");
  options.add("min_turn_clearance_m", config.route.min_turn_clearance_m,
              "turning back at a dead end, the robot keeps this far from façades (m)");
  options.add("min_facades_in_view", config.route.min_facades_in_view,
              "on the way to a dead end, the robot turns back before façades fill less than this "
              "share of its view");
  options.add("initial_still_s", config.drive.initial_still_s,
              "the robot stands still this long at the start (s)");
  options.add("initial_speed_m_s", config.drive.initial_speed_m_s,
              "speed at the start (m/s); above 0 the robot starts moving, with initial_still_s 0");
  options.add("min_speed_m_s", config.drive.min_speed_m_s, "slowest cruise speed (m/s)");
  options.add("max_speed_m_s", config.drive.max_speed_m_s, "fastest cruise speed (m/s)");
  options.add("stop_probability", config.drive.stop_probability,
              "probability that a leg is a stop");
  options.add("control_spacing_m", config.drive.control_spacing_m,
              "spacing of the path's spline control points along the route: the path rounds "
              "the route's corners over about this length (m)");
  options.add("cars_per_100m", config.clutter.cars_per_100m, "parked cars per 100 m of route");
  options.add("trees_per_100m", config.clutter.trees_per_100m, "trees per 100 m of route");
  options.add("poles_per_100m", config.clutter.poles_per_100m, "lamp posts per 100 m of route");
  options.add("tall_trees_per_100m", config.clutter.tall_trees_per_100m,
              "trees 11-16 m tall beside the façades, their crowns over the roof lines, per 100 m "
              "of route");
  options.add("cables_per_100m", config.furniture.cables_per_100m,
              "cables across the street from façade to façade, 6-8.5 m up, every other one with "
              "a lamp, per 100 m of route");
  options.add("lane_markings", config.furniture.lane_markings,
              "a dashed lane line beside the route: true or false");
  options.add("kerbs", config.furniture.kerbs,
              "kerbs between the pavements and the road: true or false");
  options.add("pedestrians_per_100m", config.clutter.pedestrians_per_100m,
              "pedestrians per 100 m of route");
  options.add("camera_calibration", config.camera_calibration,
              "OpenCV YAML calibration (empty: 640x480, OpenCV's sample lens)");
  options.add("camera_rate_hz", config.camera_rate_hz, "image rate (Hz)");
  options.add("camera_height_m", config.camera_height_m, "camera height above the ground (m)");
  options.add("camera_yaw_deg", config.camera_yaw_deg,
              "0: looking forward, 90: looking left (deg)");
  options.add("camera_pitch_deg", config.camera_pitch_deg, "camera tilt, positive up (deg)");
  options.add("camera_time_offset_s", config.camera_time_offset_s,
              "camera clock minus true time (s)");
  options.add("imu_time_offset_s", config.imu_time_offset_s, "IMU clock minus true time (s)");
  options.add("shadows", config.shadows, "cast sun shadows");
  options.add("facade_detail", config.facade_detail,
              "paint windows, doors, signs and brick on the walls (false: bare walls, each of one "
              "albedo, as an object model's faces)");
  options.add(
      "motion_blur_samples", config.motion_blur_samples,
      fmt::format("at most this many renders averaged over each frame's exposure, as many as its "
                  "motion needs (1: no motion blur; 0: {} "
                  "with the realistic camera, 1 with the ideal one)",
                  lineloc::kRealisticMotionBlurSamples));
  options.addFlag("ideal_camera", config.ideal_camera,
                  "ideal camera: 255 x radiance plus flat Gaussian noise, a fixed exposure time, "
                  "no vignetting (default: a CMOS sensor under auto-exposure)");
  options.add("full_well_e", config.sensor.full_well_e, "sensor's saturation capacity (e-)");
  options.add("read_noise_e", config.sensor.read_noise_e, "sensor's temporal dark noise (e-)");
  options.add("saturation_exposure_time_s", config.sensor.saturation_exposure_time_s,
              "exposure time in which a white surface in full sun fills the well (s)");
  options.add("target_mean_dn", config.auto_exposure.target_mean_dn,
              "mean grey level auto-exposure steers to (DN)");
  options.add("auto_exposure_tolerance", config.auto_exposure.tolerance,
              "auto-exposure's deadband around the target (fraction)");
  options.add("auto_exposure_damping", config.auto_exposure.damping,
              "fraction of the log error auto-exposure corrects per frame, 0..1");
  options.add("max_exposure_time_s", config.auto_exposure.max_exposure_time_s,
              "auto-exposure's longest exposure time, the frame period at most (s)");
  options.add("max_gain_db", config.auto_exposure.max_gain_db,
              "auto-exposure's highest analogue gain (dB)");
  options.add("noise_sigma", config.noise_sigma, "ideal camera's noise (grey levels)");
  options.add("exposure_time_s", config.exposure_time_s, "ideal camera's exposure time (s)");
  std::vector<double> camera_covered_s;
  options.addFixedSize(
      "camera_covered_s", camera_covered_s, 2,
      "START DURATION: the lens is covered (a hand, a cloth) from START to START + DURATION s "
      "after the drive's start; a frame gets the scene's light of the part of its exposure "
      "outside that window, so one inside it holds only the sensor's dark noise (the ideal "
      "camera's: black); frames are still written (empty: never covered)");
  options.add("edge_pixel_samples", config.edge_pixel_samples,
              "rays averaged over each pixel a geometric edge crosses (1: one per pixel)");
  options.add("sun_azimuth_deg", config.sun_azimuth_deg, "sun bearing from grid north (deg)");
  options.add("sun_elevation_deg", config.sun_elevation_deg, "sun elevation (deg)");
  std::string start_utc;
  options.add("start_utc", start_utc,
              "UTC time of the drive's start, e.g. 2026-05-21T08:30:00Z (empty: "
              "2023-11-14T22:13:20Z)");
  options.addFlag("sun_from_clock", config.sun_from_clock,
                  "render under the sun that stands over the site at the start, not the given one");
  options.add("ambient", config.ambient, "fraction of light in the shade, 0..1");
  options.add("imu_noise", config.imu.noise, "false: exact IMU rates and forces, no biases");
  options.add("imu_rate_hz", config.imu.rate_hz, "IMU rate (Hz)");
  options.add("gyro_noise_density", config.imu.gyro_noise_radps_per_sqrt_hz,
              "gyro white noise (rad/s/sqrt(Hz))");
  options.add("accel_noise_density", config.imu.accel_noise_mps2_per_sqrt_hz,
              "accelerometer white noise (m/s^2/sqrt(Hz))");
  options.add("gyro_random_walk", config.imu.gyro_bias_random_walk_radps2_per_sqrt_hz,
              "gyro bias random walk (rad/s^2/sqrt(Hz))");
  options.add("accel_random_walk", config.imu.accel_bias_random_walk_mps3_per_sqrt_hz,
              "accelerometer bias random walk (m/s^3/sqrt(Hz))");
  options.add("gps_rate_hz", config.gps.rate_hz, "DGPS fix rate (Hz)");
  options.add("gps_horizontal_sigma_m", config.gps.correlated_horizontal_sigma_m,
              "time-correlated horizontal DGPS error (m)");
  options.add(
      "gps_initial_error_m", config.gps.initial_horizontal_error_m,
      fmt::format("the time-correlated horizontal DGPS error at the first fix, in a direction "
                  "drawn from the seed; from there the model runs as always, the start's offset "
                  "decaying as exp(-t / {} s) while the wander of gps_horizontal_sigma_m grows "
                  "back (m; 0: the first error is drawn from that wander)",
                  config.gps.correlation_time_s));
  options.add("gps_outage_probability", config.gps.outage_probability,
              "probability per fix that an outage starts");
  options.add("compass_rate_hz", config.compass.rate_hz, "compass rate (Hz)");
  double compass_sigma_deg = config.compass.sigma_rad * 180.0 / std::numbers::pi;
  options.add("compass_sigma_deg", compass_sigma_deg, "compass white noise (deg)");
  double compass_bias_deg = 0.0;
  options.add("compass_bias_deg", compass_bias_deg,
              "constant bias added to every compass reading, clockwise positive (deg)");
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  if (config.city_model.empty()) {
    std::cerr << "lineloc-sim: --city-model is required (e.g. data/citymodels/delft.json)\n";
    return 2;
  }
  config.compass.sigma_rad = compass_sigma_deg * std::numbers::pi / 180.0;
  config.compass.bias_rad = compass_bias_deg * std::numbers::pi / 180.0;
  try {
    if (!camera_covered_s.empty()) {
      if (camera_covered_s.size() != 2) {
        throw std::invalid_argument("camera_covered_s takes two numbers: START DURATION (s)");
      }
      config.lens_cover.emplace(camera_covered_s[0], camera_covered_s[1]);
    }
    if (!start_utc.empty()) {
      config.drive.start_stamp_ns = lineloc::parseUtcTime_ns(start_utc);
    }
    lineloc::ProgressMeter meter("rendering " + config.output, "images", std::cerr,
                                 lineloc::ProgressMeter::styleOf(STDERR_FILENO));
    const lineloc::DriveSimulationSummary summary =
        lineloc::simulateDrive(config, meter.callback());
    fmt::print(
        "lineloc-sim: {} images ({:.1f} frames/s rendering on one core), {} IMU samples, {} GPS "
        "fixes, {} compass readings; route {:.0f} m with {} cars, {} trees ({} tall), {} poles, "
        "{} pedestrians, {} cables ({} with a lamp), {} lane marking dashes, {:.0f} m of kerb -> "
        "{}\n",
        summary.images, summary.images / std::max(summary.render_cpu_s, 1e-9), summary.imu_samples,
        summary.gps_fixes, summary.compass_readings, summary.route_length_m, summary.clutter.cars,
        summary.clutter.trees + summary.clutter.tall_trees, summary.clutter.tall_trees,
        summary.clutter.poles, summary.clutter.pedestrians, summary.furniture.cables,
        summary.furniture.lamps, summary.furniture.marking_dashes, summary.furniture.kerb_m,
        config.output);
    return 0;
  } catch (const std::exception& error) {
    spdlog::error("{}", error.what());
    return 1;
  }
}
