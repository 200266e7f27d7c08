// A simulated drive through a city model, written as an EuRoC/ASL dataset:
// the city's buildings plus street clutter (sim/world), a street route (planned
// through the street network between footprints, or given as waypoints), a ground robot
// driving it (RouteTrajectory), camera images rendered along it
// (sim/render), IMU, DGPS (NMEA GGA + RMC) and compass readings synthesised
// along the same trajectory (sim/sensors), and the ground truth. Every random
// choice derives from one seed: the same configuration gives the same bytes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/geodesy/site_sun.h"
#include "common/geometry/sunlight.h"
#include "common/progress/progress_meter.h"
#include "sim/render/auto_exposure.h"
#include "sim/render/camera_sensor.h"
#include "sim/render/city_renderer.h"
#include "sim/render/lens_cover.h"
#include "sim/sensors/sensor_synthesis.h"
#include "sim/world/route_trajectory.h"
#include "sim/world/street_clutter.h"
#include "sim/world/street_furniture.h"
#include "sim/world/street_network.h"
#include "sim/world/street_route.h"

namespace lineloc {

// The realistic camera's most renders per exposure: four pixels of image
// motion, a turn of 0.5 rad/s at f = 536 px over an exposure of 15 ms.
inline constexpr int kRealisticMotionBlurSamples = 8;

struct DriveSimulationConfig {
  std::string city_model;
  // CRS of the city model for the GPS; empty: the one the model names.
  std::string crs;
  // Model coordinates of the site origin; empty: the buildings' centre.
  std::vector<double> site_origin;
  std::string output;
  uint64_t seed = 1;
  double duration_s = 60.0;
  // Waypoint file; empty: a route is planned through the street network.
  std::string waypoints;
  StreetNetworkOptions network;
  StreetRouteOptions route;
  RouteDriveOptions drive;
  StreetClutterOptions clutter;
  StreetFurnitureOptions furniture;
  // OpenCV YAML calibration; empty: a 640x480 camera with OpenCV's sample lens.
  std::string camera_calibration;
  double camera_rate_hz = 20.0;
  double camera_height_m = 1.5;
  // 0: looking forward; 90: looking left.
  double camera_yaw_deg = 0.0;
  // Positive: looking up.
  double camera_pitch_deg = 0.0;
  // Stamps of the camera and the IMU are their clock's: true time + offset.
  double camera_time_offset_s = 0.0;
  double imu_time_offset_s = 0.0;
  // Render options.
  bool shadows = true;
  // False: bare walls without windows, doors, signs or brick, and no façade
  // detail edges written.
  bool facade_detail = true;
  int edge_pixel_samples = RenderOptions{}.edge_pixel_samples;
  // At most this many renders averaged over each frame's exposure, as many as
  // its motion needs (CityRenderer::renderExposureRadiance); 0: kRealisticMotionBlurSamples
  // with the realistic camera, 1 (no blur) with the ideal one.
  int motion_blur_samples = 0;
  // The realistic camera (CameraSensor under AutoExposure; its exposure time
  // capped by the frame period too), or the ideal one: 255 x radiance plus
  // Gaussian noise of noise_sigma grey levels, a fixed exposure_time_s, no
  // vignetting.
  bool ideal_camera = false;
  CameraSensorOptions sensor;
  AutoExposureOptions auto_exposure;
  double noise_sigma = 2.0;
  double exposure_time_s = 0.008;
  // The lens covered over a window of the drive, its times in seconds from the
  // drive's start (true time, not the camera's clock). Each frame is exposed
  // with the light of the part of its exposure, centred on its stamp, the lens
  // was open (LensCover::openFraction); frames inside the window are still
  // written, the realistic camera's holding its dark noise alone and metered by
  // auto-exposure as such (so the frames after the window start overexposed
  // until it settles again), the ideal camera's uniform black (0).
  std::optional<LensCover> lens_cover;
  double sun_azimuth_deg = 135.0;  // clockwise from grid north
  double sun_elevation_deg = 40.0;
  // Instead: the sun over the site at the drive's start (drive.start_stamp_ns,
  // UTC), as common/geodesy/site_sun.h places it. The sun moves 0.25 degree
  // a minute; the drive is rendered under its start's.
  bool sun_from_clock = false;
  double ambient = 0.35;
  sim::ImuModel imu;
  sim::GpsModel gps;
  sim::CompassModel compass;
};

struct DriveSimulationSummary {
  int images = 0;
  int imu_samples = 0;
  int gps_fixes = 0;
  int compass_readings = 0;
  double route_length_m = 0.0;
  StreetClutterCounts clutter;
  StreetFurnitureCounts furniture;
  // Thread CPU time spent rendering (s).
  double render_cpu_s = 0.0;
};

// `progress(done, total)` reports the images written. Throws
// std::runtime_error naming the input that is missing or malformed,
// std::invalid_argument naming a camera option out of its range.
DriveSimulationSummary simulateDrive(const DriveSimulationConfig& config,
                                     const ProgressCallback& progress = nullptr);

// The sun the drive's images are rendered under, given by its azimuth and
// elevation; throws std::invalid_argument for an elevation outside [-90, 90]
// deg, an ambient fraction outside [0, 1], or a config whose sun is the clock's.
Sunlight drivingSunlight(const DriveSimulationConfig& config);

// The same, or the clock's sun over `site` when config.sun_from_clock; throws
// std::runtime_error when that is below the horizon.
Sunlight drivingSunlight(const DriveSimulationConfig& config, const SiteSun& site);

}  // namespace lineloc
