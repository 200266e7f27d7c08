// lineloc-track: model-based tracking of a camera in a city model, offline —
// the backbone's matching pipeline without DDS or a database, on a folder of
// images (or an EuRoC/ASL camera folder) and a model file. Writes one pose per
// frame (TUM) and, when asked, an overlay PNG per frame.
//
// It composes the robot's front end (robot/vision) with the backbone's
// matching, so it links both: it is a tool, not a library either depends on.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "backbone/tracker/model_file.h"
#include "backbone/tracker/tracking_overlay.h"
#include "common/camera/camera_calibration.h"
#include "common/config/program_options.h"
#include "common/trajectory/tum_trajectory.h"
#include "robot/input/image_sequence.h"
#include "robot/vision/features/feature_extractor.h"

namespace {

struct TrackConfig {
  std::string model;
  std::string images;
  std::string camera_calibration;
  std::vector<double> init = {0, 0, 1.5, 0, 0, 0, 1};
  double init_position_sigma_m = 0.5;
  double init_rotation_sigma_deg = 2.0;
  std::vector<double> origin;
  int crs = 0;
  std::string out = "poses.tum";
  std::string overlay_dir;
  std::vector<double> sun_deg;
  double ambient = 0.35;
  lineloc::FeatureExtractorOptions extractor = lineloc::trackingFrontEndOptions();
};

int run(const TrackConfig& config) {
  using namespace lineloc;
  if (config.init.size() != 7) {
    throw std::runtime_error("init needs 7 numbers: tx ty tz qx qy qz qw");
  }
  if (!config.origin.empty() && config.origin.size() != 3) {
    throw std::runtime_error("origin needs 3 numbers: x y z");
  }
  std::optional<Eigen::Vector3d> origin;
  if (config.origin.size() == 3) {
    origin = Eigen::Vector3d(config.origin[0], config.origin[1], config.origin[2]);
  }
  const LocalModel local = readLocalModel(
      config.model, origin, config.crs > 0 ? std::optional<int>(config.crs) : std::nullopt);
  std::cout << fmt::format(
      "lineloc-track: {} buildings, {} lines, {} faces; frame = model CRS minus origin ({:.3f}, "
      "{:.3f}, {:.3f})\n",
      local.buildings, local.model.lines.size(), local.model.faces.size(), local.origin.x(),
      local.origin.y(), local.origin.z());
  const CameraCalibration calibration = readCameraCalibration(config.camera_calibration);
  PoseWithCovariance start;
  start.pose =
      makePose({config.init[0], config.init[1], config.init[2]},
               Eigen::Quaterniond(config.init[6], config.init[3], config.init[4], config.init[5]));
  start.covariance = diagonalPoseCovariance(config.init_position_sigma_m,
                                            config.init_rotation_sigma_deg * M_PI / 180.0);
  TrackerOptions tracker_options;
  if (!config.sun_deg.empty()) {
    tracker_options.localizer.visibility.sunlight =
        Sunlight::fromAzimuthElevation(config.sun_deg[0], config.sun_deg[1], config.ambient);
  }
  ModelTracker tracker(local.model, calibration.camera, start, tracker_options);
  FeatureExtractor extractor(calibration, config.extractor);
  TumWriter trajectory(config.out);
  if (!config.overlay_dir.empty()) {
    std::filesystem::create_directories(config.overlay_dir);
  }
  int aligned = 0;
  const std::vector<FrameRef> frames = listImageSequence(config.images);
  for (size_t index = 0; index < frames.size(); ++index) {
    const cv::Mat image = cv::imread(frames[index].path, cv::IMREAD_COLOR);
    if (image.empty()) {
      throw std::runtime_error(fmt::format("cannot read image '{}'", frames[index].path));
    }
    const FrameFeatures& features = extractor.extract(image);
    const TrackedFrame frame = tracker.track(features.segments, features.corners);
    aligned += frame.alignment.status == AlignmentStatus::kOk ? 1 : 0;
    spdlog::info("frame {}: {}{} ({} inliers){}", index, toString(frame.alignment.status),
                 frame.acquired ? " after a search" : "", frame.alignment.inliers,
                 frame.alignment.message.empty() ? "" : ": " + frame.alignment.message);
    trajectory.write(
        {frames[index].stamp_ns.value_or(static_cast<int64_t>(index)), frame.T_world_camera.pose});
    if (!config.overlay_dir.empty()) {
      cv::imwrite(fmt::format("{}/frame_{:06d}.png", config.overlay_dir, index),
                  drawTrackingOverlay(image, features.segments, frame, calibration));
    }
  }
  std::cout << fmt::format("lineloc-track: {} frames, {} aligned; poses in {}\n", frames.size(),
                           aligned, config.out);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  TrackConfig config;
  lineloc::ProgramOptions options("lineloc-track",
                                  "Model-based camera tracking in a city model, offline");
  options.add("model", config.model, "city model file (CityJSON, CityJSON Lines, OBJ, GeoJSON)");
  options.add("images", config.images, "image folder or EuRoC/ASL camera folder");
  options.add("camera_calibration", config.camera_calibration,
              "camera calibration (OpenCV YAML layout)");
  options.addFixedSize("init", config.init, 7,
                       "first frame's T_world_camera: tx ty tz qx qy qz qw");
  options.add("init_position_sigma_m", config.init_position_sigma_m,
              "standard deviation of the initial position (m)");
  options.add("init_rotation_sigma_deg", config.init_rotation_sigma_deg,
              "standard deviation of the initial rotation (degrees)");
  options.addFixedSize(
      "origin", config.origin, 3,
      "x y z subtracted from model coordinates (default: the model's lowest corner)");
  options.add("crs", config.crs, "EPSG code for a model file that names no CRS");
  options.add("out", config.out, "TUM trajectory file written");
  options.add("overlay_dir", config.overlay_dir, "folder for overlay PNGs (empty: none)");
  options.addFixedSize("sun", config.sun_deg, 2,
                       "sun azimuth clockwise from grid north and elevation (deg): corners "
                       "between walls it lights alike are no edges (default: sun unknown)");
  options.add("ambient", config.ambient, "with --sun: fraction of the light in the shade, 0..1");
  options.add("min_edge_gradient", config.extractor.edges.min_gradient,
              "edge threshold of the line extraction (grey levels per pixel)");
  options.add("min_segment_contrast", config.extractor.lines.min_contrast,
              "weakest segment tracked (mean grey-level step across it)");
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  try {
    return run(config);
  } catch (const std::exception& error) {
    spdlog::error("{}", error.what());
    return 1;
  }
}
