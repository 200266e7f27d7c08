// What lineloc-track does: model-based tracking of a camera in a city model,
// offline. The robot's front end (robot/vision/features) extracts each
// image's segments and corners; the backbone's ModelTracker
// (backbone/tracker/model_tracker.h) aligns the model's lines to them from
// the previous frame's pose, searching when it loses the camera. No DDS, no
// database: a model file, a folder of images (or an EuRoC/ASL camera folder)
// and the first frame's predicted pose in; one pose per frame (TUM) out, and
// an overlay PNG per frame when asked.
//
// It composes the robot's and the backbone's libraries, so it belongs to
// neither: backbone/ never includes robot/.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "robot/vision/features/feature_extractor.h"

namespace lineloc {

struct OfflineTrackingConfig {
  // CityJSON, CityJSON Lines, OBJ or GeoJSON footprints.
  std::string city_model;
  // "EPSG:N" for a model file that names no CRS.
  std::string city_model_crs;
  // Model coordinates x y z of the site origin: poses are in the model's CRS
  // minus it. Empty: the model's lowest corner, rounded down.
  std::vector<double> site_origin;
  std::string images;
  // OpenCV YAML layout.
  std::string camera_calibration;
  // The first frame's T_world_camera: tx ty tz qx qy qz qw.
  std::vector<double> predicted_pose = {0, 0, 1.5, 0, 0, 0, 1};
  double predicted_position_sigma_m = 0.5;
  double predicted_rotation_sigma_deg = 2.0;
  // TUM trajectory written.
  std::string out = "poses.tum";
  // Folder of overlay PNGs; empty: none.
  std::string overlay_dir;
  // Sun azimuth clockwise from grid north and elevation (deg); empty: unknown.
  std::vector<double> sun_deg;
  // With a sun: fraction of the light in the shade, 0..1.
  double ambient = 0.35;
  FeatureExtractorOptions extractor = trackingFrontEndOptions();
};

struct OfflineTrackingSummary {
  int frames = 0;
  // Frames whose alignment was OK.
  int aligned = 0;
};

// Tracks every frame, logging each frame's outcome, and writes the poses
// (and overlays). Writes what the model holds and the summary to `out`.
// Throws std::runtime_error naming the option or file that is malformed or
// unreadable.
OfflineTrackingSummary runOfflineTracking(const OfflineTrackingConfig& config, std::ostream& out);

}  // namespace lineloc
