#include "sim/dataset/drive_simulation.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include "common/geodesy/site_projection.h"
#include "common/time/clock.h"
#include "common/time/utc_time.h"
#include "sim/dataset/euroc_writer.h"
#include "sim/render/city_renderer.h"
#include "sim/render/sample_camera.h"
#include "sim/world/city_mesh.h"
#include "sim/world/clutter_boxes.h"
#include "sim/world/facade_edges.h"
#include "sim/world/occupancy_map.h"
#include "sim/world/waypoint_file.h"

namespace lineloc {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Auto-exposure meets the first frame already settled on it, as a camera
// switched on before the drive: at most this many meterings of it.
constexpr int kSettlingMeterings = 64;

double threadCpuSeconds() {
  return 1e-9 * static_cast<double>(threadCpuClockNs());
}

int64_t seconds_to_ns(double seconds) {
  return static_cast<int64_t>(std::llround(seconds * 1e9));
}

// Camera in the body frame (x forward, y left, z up): optical axis along the
// body's yawed and pitched forward direction, image x to its right.
Eigen::Isometry3d bodyToCamera(const DriveSimulationConfig& config) {
  Eigen::Matrix3d R_forward_camera;
  R_forward_camera << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Eigen::Isometry3d T_body_camera = Eigen::Isometry3d::Identity();
  T_body_camera.linear() =
      (Eigen::AngleAxisd(config.camera_yaw_deg * kDegree, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(-config.camera_pitch_deg * kDegree, Eigen::Vector3d::UnitY()))
          .toRotationMatrix() *
      R_forward_camera;
  T_body_camera.translation() =
      Eigen::Vector3d(0.0, 0.0, config.camera_height_m - config.drive.body_height_m);
  return T_body_camera;
}

Eigen::Isometry3d bodyPose(const sim::TruthSample& sample) {
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
  T_world_body.linear() = sample.q_world_body.toRotationMatrix();
  T_world_body.translation() = sample.p_world_body;
  return T_world_body;
}

// f(i) for i in [first, first + count), one thread each; adds the thread CPU
// time they spent to cpu_s.
template <typename F>
auto inParallel(size_t first, size_t count, const F& f, double& cpu_s) {
  using Result = decltype(f(first));
  std::vector<std::future<std::pair<Result, double>>> running;
  for (size_t i = first; i < first + count; ++i) {
    running.push_back(std::async(std::launch::async, [&f, i] {
      const double start_s = threadCpuSeconds();
      Result result = f(i);
      return std::pair{std::move(result), threadCpuSeconds() - start_s};
    }));
  }
  std::vector<Result> results;
  for (auto& result : running) {
    auto [value, thread_cpu_s] = result.get();
    results.push_back(std::move(value));
    cpu_s += thread_cpu_s;
  }
  return results;
}

RenderOptions renderOptions(const DriveSimulationConfig& config, const Sunlight& sun,
                            double ground_z_m) {
  RenderOptions options;
  options.shading.sun_direction = sun.direction_world.cast<float>();
  options.shading.ambient = static_cast<float>(sun.ambient_fraction);
  options.shading.facade_detail = config.facade_detail;
  options.ground_z_m = static_cast<float>(ground_z_m);
  options.shadows = config.shadows;
  options.noise_sigma = static_cast<float>(config.noise_sigma);
  options.motion_blur_samples = config.motion_blur_samples != 0 ? config.motion_blur_samples
                                : config.ideal_camera           ? 1
                                                                : kRealisticMotionBlurSamples;
  options.edge_pixel_samples = config.edge_pixel_samples;
  return options;
}

std::string resolveCrs(const DriveSimulationConfig& config, const citymodel::CityModel& model) {
  if (!config.crs.empty()) {
    return config.crs;
  }
  if (!model.epsg) {
    throw std::runtime_error(fmt::format(
        "{}: the city model names no CRS; give one with --city-model-crs (e.g. EPSG:7415)",
        config.city_model));
  }
  return fmt::format("EPSG:{}", *model.epsg);
}

std::vector<Eigen::Vector2d> planRoute(const DriveSimulationConfig& config,
                                       const OccupancyMap& map) {
  if (!config.waypoints.empty()) {
    return readWaypointFile(config.waypoints);
  }
  StreetRouteOptions options = config.route;
  // Long enough to drive the whole time at top speed.
  options.length_m = config.drive.max_speed_m_s * config.duration_s + 20.0;
  options.seed = static_cast<uint32_t>(config.seed);
  const StreetRoute route = planStreetRoute(buildStreetNetwork(map, config.network), map, options);
  if (route.status == RouteStatus::kNoStreets) {
    throw std::runtime_error(
        fmt::format("{}: no street with {} m clearance from the façades to drive and turn in",
                    config.city_model, config.network.min_clearance_m));
  }
  if (route.status == RouteStatus::kTooShort) {
    spdlog::warn("the street network allows only {:.0f} m of route; the robot stops at its end",
                 route.length_m);
  }
  return route.waypoints;
}

void writeWorldFile(const DriveSimulationConfig& config, const std::string& crs,
                    const CityMesh& city, const Sunlight& sun,
                    const std::vector<Eigen::Vector2d>& route) {
  const std::filesystem::path root(config.output);
  std::ofstream world(root / "world.yaml");
  world << fmt::format(
      "# lineloc-sim: the world this dataset was rendered from\ncity_model: \"{}\"\ncrs: \"{}\"\n"
      "site_origin: [{:.3f}, {:.3f}, {:.3f}]\nground_z_m: {:.3f}\nseed: {}\nstart_utc: {}\n"
      "sun_azimuth_deg: {:.3f}\nsun_elevation_deg: {:.3f}\nambient: {:.3f}\n",
      config.city_model, crs, city.site_origin.x(), city.site_origin.y(), city.site_origin.z(),
      city.ground_z_m, config.seed, formatUtcTime(config.drive.start_stamp_ns), sun.azimuth_deg(),
      sun.elevation_deg(), sun.ambient_fraction);
  std::ofstream waypoints(root / "route.txt");
  waypoints << "# x y (m, site frame): the route the robot drove\n";
  for (const Eigen::Vector2d& point : route) {
    waypoints << fmt::format("{:.3f} {:.3f}\n", point.x(), point.y());
  }
}

// The façade detail near the drive, as ground truth for lines learnt from its
// images.
void writeFacadeEdgeFile(const DriveSimulationConfig& config, const CityMesh& city,
                         const RouteTrajectory& trajectory) {
  constexpr int64_t kSpacing_ns = 500'000'000;
  std::vector<Eigen::Vector2d> positions;
  for (int64_t stamp_ns = trajectory.startStamp_ns(); stamp_ns <= trajectory.endStamp_ns();
       stamp_ns += kSpacing_ns) {
    positions.push_back(trajectory.at(stamp_ns).p_world_body.head<2>());
  }
  writeFacadeEdges(
      (std::filesystem::path(config.output) / "facade_edges.txt").string(),
      config.facade_detail ? facadeDetailEdges(city, positions) : std::vector<FacadeEdge>{});
}

void writeSensors(const DriveSimulationConfig& config, const RouteTrajectory& trajectory,
                  const SiteProjection& projection, EurocWriter& writer,
                  DriveSimulationSummary& summary) {
  const int64_t imu_offset_ns = seconds_to_ns(config.imu_time_offset_s);
  const std::vector<sim::SimImuSample> imu =
      sim::synthesiseImu(trajectory, config.imu, config.seed * 4 + 1);
  for (const sim::SimImuSample& sample : imu) {
    writer.writeImu(sample.stamp_ns + imu_offset_ns, sample.gyro_radps, sample.accel_mps2);
    const sim::TruthSample truth = trajectory.at(sample.stamp_ns);
    writer.writeGroundTruth({sample.stamp_ns, bodyPose(truth), truth.v_world_body,
                             sample.true_gyro_bias_radps, sample.true_accel_bias_mps2});
  }
  summary.imu_samples = static_cast<int>(imu.size());
  for (const sim::SimGpsFix& fix :
       sim::synthesiseGps(trajectory, config.gps, config.seed * 4 + 2)) {
    // GGA and RMC of one epoch share its stamp; the writer wants increasing stamps.
    int64_t stamp_ns = fix.stamp_ns;
    for (const std::string& sentence : sim::formatNmeaEpoch(fix, projection)) {
      writer.writeNmea(stamp_ns++, sentence);
    }
    ++summary.gps_fixes;
  }
  const double grid_bearing =
      projection.gridBearingOfTrueNorth_rad(projection.toGeodetic(Eigen::Vector3d::Zero()));
  for (const sim::SimCompassReading& reading :
       sim::synthesiseCompass(trajectory, config.compass, grid_bearing, config.seed * 4 + 3)) {
    writer.writeCompass(reading.stamp_ns, reading.magnetic_heading_rad);
    ++summary.compass_readings;
  }
}

}  // namespace

Sunlight drivingSunlight(const DriveSimulationConfig& config) {
  if (config.sun_from_clock) {
    throw std::invalid_argument("the clock's sun needs the site: drivingSunlight(config, site)");
  }
  return Sunlight::fromAzimuthElevation(config.sun_azimuth_deg, config.sun_elevation_deg,
                                        config.ambient);
}

Sunlight drivingSunlight(const DriveSimulationConfig& config, const SiteSun& site) {
  if (!config.sun_from_clock) {
    return drivingSunlight(config);
  }
  const std::optional<Sunlight> sun = site.at(config.drive.start_stamp_ns);
  if (!sun) {
    throw std::runtime_error(fmt::format(
        "the sun is below the horizon at {} at latitude {:.4f}, longitude {:.4f}: nothing to "
        "shade with; start by day or give the sun's azimuth and elevation",
        formatUtcTime(config.drive.start_stamp_ns), site.place().latitude_deg,
        site.place().longitude_deg));
  }
  return *sun;
}

DriveSimulationSummary simulateDrive(const DriveSimulationConfig& config,
                                     const ProgressCallback& progress) {
  if (!(config.camera_rate_hz > 0.0) || !(config.duration_s > 0.0) || config.output.empty()) {
    throw std::runtime_error("camera_rate_hz and duration_s must be positive and output given");
  }
  DriveSimulationSummary summary;
  const citymodel::CityModel model = readCityModelFile(config.city_model);
  const std::string crs = resolveCrs(config, model);
  const Eigen::Vector3d origin = siteOriginOf(model, config.site_origin);
  const CityMesh city = buildCityMesh(model, origin);
  const OccupancyMap map(city.mesh);
  const std::vector<Eigen::Vector2d> route = planRoute(config, map);
  summary.route_length_m = polylineLength(route);
  SceneMesh scene = city.mesh;
  const auto ground_height_m = [&city](const Eigen::Vector2d& xy) {
    return groundHeightAt(city, xy);
  };
  StreetClutterOptions clutter = config.clutter;
  clutter.seed = static_cast<uint32_t>(config.seed * 4);
  summary.clutter =
      addStreetClutter(map, route, ground_height_m, clutter, kFirstClutterObjectId, scene);
  StreetFurnitureOptions furniture = config.furniture;
  furniture.seed = static_cast<uint32_t>(config.seed * 4 + 1);
  summary.furniture =
      addStreetFurniture(map, route, ground_height_m, furniture, kFirstFurnitureObjectId, scene);
  RouteDriveOptions drive = config.drive;
  drive.duration_s = config.duration_s;
  drive.seed = config.seed;
  const RouteTrajectory trajectory(route, ground_height_m, drive);

  const CameraCalibration calibration = config.camera_calibration.empty()
                                            ? opencvSampleCamera()
                                            : readCameraCalibration(config.camera_calibration);
  EurocDatasetSpec spec;
  spec.camera = calibration;
  spec.T_body_camera = bodyToCamera(config);
  spec.camera_rate_hz = config.camera_rate_hz;
  spec.imu = {config.imu.rate_hz, config.imu.gyro_noise_radps_per_sqrt_hz,
              config.imu.gyro_bias_random_walk_radps2_per_sqrt_hz,
              config.imu.accel_noise_mps2_per_sqrt_hz,
              config.imu.accel_bias_random_walk_mps3_per_sqrt_hz};
  const SiteProjection projection(crs, origin);
  const Sunlight sun = drivingSunlight(config, SiteSun(projection, config.ambient));
  EurocWriter writer(config.output, spec);
  writeWorldFile(config, crs, city, sun, route);
  writeFacadeEdgeFile(config, city, trajectory);
  writeClutterBoxes((std::filesystem::path(config.output) / "clutter.txt").string(),
                    clutterBoxes(scene, kFirstClutterObjectId));
  writeSensors(config, trajectory, projection, writer, summary);

  const CityRenderer renderer(scene, calibration, renderOptions(config, sun, city.ground_z_m));
  const int64_t period_ns = seconds_to_ns(1.0 / config.camera_rate_hz);
  const int64_t camera_offset_ns = seconds_to_ns(config.camera_time_offset_s);
  std::vector<int64_t> stamps_ns;
  for (int64_t stamp_ns = trajectory.startStamp_ns(); stamp_ns <= trajectory.endStamp_ns();
       stamp_ns += period_ns) {
    stamps_ns.push_back(stamp_ns);
  }
  const auto cameraPose = [&](int64_t stamp_ns) {
    return bodyPose(trajectory.at(stamp_ns)) * spec.T_body_camera;
  };
  // Image i's noise is drawn from seed * 1000003 + i, so the bytes do not
  // depend on how many frames render at once.
  const auto noiseSeed = [&](size_t i) {
    return config.seed * 1'000'003 + static_cast<uint64_t>(i);
  };
  // The share of the scene's light that reaches the sensor over frame i's
  // exposure of `exposure_time_s`, centred on its stamp.
  const auto openFraction = [&](size_t i, double exposure_time_s) {
    if (!config.lens_cover) {
      return 1.0;
    }
    const double stamp_s = 1e-9 * static_cast<double>(stamps_ns[i] - trajectory.startStamp_ns());
    return config.lens_cover->openFraction(stamp_s - 0.5 * exposure_time_s,
                                           stamp_s + 0.5 * exposure_time_s);
  };
  const auto renderIdeal = [&](size_t i) {
    const double light_fraction = openFraction(i, config.exposure_time_s);
    if (light_fraction == 0.0) {
      return cv::Mat(calibration.camera.height, calibration.camera.width, CV_8UC1, cv::Scalar(0));
    }
    const int64_t half_exposure_ns = seconds_to_ns(0.5 * config.exposure_time_s);
    return renderer.renderImage(cameraPose(stamps_ns[i] - half_exposure_ns),
                                cameraPose(stamps_ns[i] + half_exposure_ns), noiseSeed(i),
                                static_cast<float>(light_fraction));
  };
  std::optional<CameraSensor> sensor;
  std::optional<AutoExposure> auto_exposure;
  std::ofstream exposures;
  const double max_exposure_time_s =
      std::min(config.auto_exposure.max_exposure_time_s, 1.0 / config.camera_rate_hz);
  if (!config.ideal_camera) {
    sensor.emplace(renderer.rays(), config.sensor);
    AutoExposureOptions options = config.auto_exposure;
    options.max_exposure_time_s = max_exposure_time_s;
    auto_exposure.emplace(options, ExposureSettings{options.max_exposure_time_s, 0.0});
    exposures.open(std::filesystem::path(config.output) / "cam0" / "exposure.csv");
    exposures << "#timestamp [ns],exposure_time [s],gain [dB]\n";
  }
  // Frames render one per core at a time and are written in order. The
  // realistic camera's auto-exposure meters each frame, in order, by the
  // noise-free mean DN of its render at the stamp times the frame's open
  // fraction; the exposure it sets then fixes the frame's motion blur and
  // noise. A frame dark under the longest exposure is dark under any: its
  // scene is not rendered.
  const cv::Mat dark_radiance =
      cv::Mat::zeros(calibration.camera.height, calibration.camera.width, CV_32FC1);
  const auto isDark = [&](size_t i) { return openFraction(i, max_exposure_time_s) == 0.0; };
  // The radiance that reaches the sensor: `scene` times the open fraction.
  const auto throughLens = [&](const cv::Mat& scene, size_t i, double exposure_time_s) {
    const double light_fraction = openFraction(i, exposure_time_s);
    return light_fraction == 1.0   ? scene
           : light_fraction == 0.0 ? dark_radiance
                                   : cv::Mat(scene * light_fraction);
  };
  const size_t cores = std::max(1u, std::thread::hardware_concurrency());
  for (size_t first = 0; first < stamps_ns.size(); first += cores) {
    const size_t count = std::min(cores, stamps_ns.size() - first);
    std::vector<cv::Mat> images;
    if (config.ideal_camera) {
      images = inParallel(first, count, renderIdeal, summary.render_cpu_s);
    } else {
      const std::vector<cv::Mat> centres = inParallel(
          first, count,
          [&](size_t i) {
            return isDark(i) ? dark_radiance : renderer.renderRadiance(cameraPose(stamps_ns[i]));
          },
          summary.render_cpu_s);
      for (int metering = 0; first == 0 && metering < kSettlingMeterings; ++metering) {
        const ExposureSettings& metered = auto_exposure->settings();
        auto_exposure->update(sensor->meanSignal_dn(
            throughLens(centres.front(), 0, metered.exposure_time_s), metered));
      }
      std::vector<ExposureSettings> settings;
      for (size_t k = 0; k < count; ++k) {
        settings.push_back(auto_exposure->settings());
        auto_exposure->update(sensor->meanSignal_dn(
            throughLens(centres[k], first + k, settings.back().exposure_time_s), settings.back()));
      }
      images = inParallel(
          first, count,
          [&](size_t i) {
            const ExposureSettings& frame = settings[i - first];
            const int64_t half_exposure_ns = seconds_to_ns(0.5 * frame.exposure_time_s);
            const cv::Mat radiance =
                isDark(i) ? dark_radiance
                          : renderer.renderExposureRadiance(
                                cameraPose(stamps_ns[i] - half_exposure_ns),
                                cameraPose(stamps_ns[i] + half_exposure_ns), centres[i - first]);
            return sensor->expose(throughLens(radiance, i, frame.exposure_time_s), frame,
                                  noiseSeed(i));
          },
          summary.render_cpu_s);
      for (size_t k = 0; k < count; ++k) {
        exposures << fmt::format("{},{:.6e},{:.3f}\n", stamps_ns[first + k] + camera_offset_ns,
                                 settings[k].exposure_time_s, settings[k].gain_db);
      }
    }
    for (const cv::Mat& image : images) {
      const int64_t stamp_ns = stamps_ns[summary.images];
      writer.writeImage(stamp_ns + camera_offset_ns, image);
      writer.writeCameraGroundTruth({stamp_ns, cameraPose(stamp_ns)});
      ++summary.images;
      if (progress) {
        progress(summary.images, stamps_ns.size());
      }
    }
  }
  return summary;
}

}  // namespace lineloc
