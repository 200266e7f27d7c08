// lineloc-track: model-based tracking of a camera in a city model, offline
// (apps/offline_tracking.h).
#include <spdlog/spdlog.h>

#include <iostream>

#include "apps/offline_tracking.h"
#include "common/config/program_options.h"

int main(int argc, char** argv) {
  lineloc::OfflineTrackingConfig config;
  lineloc::ProgramOptions options("lineloc-track",
                                  "Model-based camera tracking in a city model, offline");
  lineloc::addRecordedDriveOptions(options, config.drive);
  options.add("model_up_axis", config.model_up_axis,
              "axis the model file holds up: z, or y (as many object models in OBJ)");
  options.addFixedSize("predicted_pose", config.predicted_pose, 7,
                       "first frame's predicted T_world_camera: tx ty tz qx qy qz qw");
  options.add("predicted_position_sigma_m", config.predicted_position_sigma_m,
              "standard deviation of the predicted position (m)");
  options.add("predicted_rotation_sigma_deg", config.predicted_rotation_sigma_deg,
              "standard deviation of the predicted rotation (degrees)");
  options.add("out", config.out, "TUM trajectory file written");
  options.add("fix_log_out", config.fix_log_out,
              "fix log written, each frame's status and covariance (empty: none)");
  options.add("overlay_dir", config.overlay_dir, "folder for overlay PNGs (empty: none)");
  options.add("min_edge_gradient", config.extractor.edges.min_gradient,
              "edge threshold of the line extraction (grey levels per pixel)");
  options.add("min_segment_contrast", config.extractor.lines.min_contrast,
              "weakest segment tracked (mean grey-level step across it)");
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  try {
    lineloc::runOfflineTracking(config, std::cout);
    return 0;
  } catch (const std::exception& error) {
    spdlog::error("{}", error.what());
    return 1;
  }
}
