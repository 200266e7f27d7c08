// lineloc-features: runs the robot's vision front end on one image and shows
// what the robot would send: the segments and corners as text on standard
// output, and an overlay on the undistorted image.
#include <spdlog/spdlog.h>

#include <iostream>

#include "common/config/program_options.h"
#include "robot/vision/features/features_tool.h"

namespace {

void addOptions(lineloc::ProgramOptions& options, lineloc::FeaturesToolConfig& config) {
  options.addPositional("image", config.image, "image file (8-bit grey or colour)", true);
  lineloc::EdgeDetectorOptions& edges = config.extractor.edges;
  lineloc::LineExtractorOptions& lines = config.extractor.lines;
  lineloc::ForstnerOptions& corners = config.extractor.corners;
  options.add("camera_calibration", config.camera_calibration,
              "camera calibration (OpenCV YAML layout); empty: an ideal camera of the image size");
  options.add("out", config.out, "overlay image to write; empty: none");
  options.add("smoothing_sigma_px", edges.smoothing_sigma_px,
              "Gaussian pre-smoothing (px), >= 0.5; 0: none");
  options.add("min_edge_gradient", edges.min_gradient,
              "edge threshold's floor (grey levels per px); above it, the noise sets it");
  options.add("split_distance_px", lines.split_distance_px, "split-and-merge tolerance (px)");
  options.add("min_segment_length_px", lines.min_length_px, "shortest segment kept (px)");
  options.add("min_segment_contrast", lines.min_contrast,
              "weakest segment kept (mean grey-level step), besides the a contrario test");
  options.add("max_false_alarms", lines.max_false_alarms,
              "a contrario test: expected segments from noise alone per image");
  options.add("max_gap_px", lines.merge.max_gap_px,
              "largest gap bridged between collinear segments (px)");
  options.add("detect_corners", config.extractor.detect_corners, "run the Förstner operator");
  options.add("min_roundness", corners.min_roundness, "Förstner roundness threshold q");
  options.add("weight_factor", corners.weight_factor, "Förstner weight threshold / mean weight");
  options.add("max_corners", corners.max_corners, "most corners kept (strongest)");
}

}  // namespace

int main(int argc, char** argv) {
  lineloc::FeaturesToolConfig config;
  lineloc::ProgramOptions options(
      "lineloc-features", "line segments and corners of one image, as the robot sends them");
  addOptions(options, config);
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  try {
    const lineloc::FeaturesToolSummary summary = lineloc::runFeaturesTool(config, std::cout);
    spdlog::info(
        "{}: noise sigma {:.2f} grey levels, {} segments ({} rejected as explained by the noise), "
        "{} corners",
        config.image, summary.noise_sigma, summary.segments, summary.rejected_segments,
        summary.corners);
    return 0;
  } catch (const std::exception& error) {
    spdlog::error("{}", error.what());
    return 1;
  }
}
