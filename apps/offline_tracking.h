// What lineloc-track does: model-based tracking of a camera in a city model,
// or in an object's model in its own frame, offline. The robot's front end (robot/vision/features)
// extracts each image's segments and corners; the backbone's ModelTracker
// (backbone/tracker/model_tracker.h) aligns the model's lines to them from
// the previous frame's pose, searching when it loses the camera. No DDS, no
// database: a model file, a folder of images (or an EuRoC/ASL camera folder)
// and the first frame's predicted pose in; one pose per frame (TUM) out, and
// an overlay PNG per frame and a fix log when asked. Poses in and out are in
// the model's own axes (y-up for a y-up model) minus the site origin; the
// tracker works z-up.
//
// It composes the robot's and the backbone's libraries, so it belongs to
// neither: backbone/ never includes robot/.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "apps/recorded_drive.h"
#include "robot/vision/features/feature_extractor.h"

namespace lineloc {

struct OfflineTrackingConfig {
  RecordedDrive drive;
  // The axis the model file holds up: "z" or "y".
  std::string model_up_axis = "z";
  // The first frame's T_world_camera: tx ty tz qx qy qz qw.
  std::vector<double> predicted_pose = {0, 0, 1.5, 0, 0, 0, 1};
  double predicted_position_sigma_m = 0.5;
  double predicted_rotation_sigma_deg = 2.0;
  // TUM trajectory written.
  std::string out = "poses.tum";
  // Fix log written (common/trajectory/fix_log.h), each frame's answer with
  // its status and covariance as the robot logs the backbone's, so that
  // lineloc-enrich and lineloc-eval take it; empty: none.
  std::string fix_log_out;
  // Folder of overlay PNGs; empty: none.
  std::string overlay_dir;
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
