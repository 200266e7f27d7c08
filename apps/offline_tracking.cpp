#include "apps/offline_tracking.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <ostream>

#include "backbone/tracker/model_file.h"
#include "backbone/tracker/model_tracker.h"
#include "backbone/tracker/tracking_overlay.h"
#include "common/camera/camera_calibration.h"
#include "common/trajectory/tum_trajectory.h"
#include "db/citymodel/city_model.h"
#include "robot/input/image_sequence.h"

namespace lineloc {
namespace {

std::optional<Eigen::Vector3d> siteOriginOf(const OfflineTrackingConfig& config) {
  if (config.site_origin.empty()) {
    return std::nullopt;
  }
  if (config.site_origin.size() != 3) {
    throw std::runtime_error("site_origin needs 3 numbers: x y z");
  }
  return Eigen::Vector3d(config.site_origin[0], config.site_origin[1], config.site_origin[2]);
}

PoseWithCovariance predictedPoseOf(const OfflineTrackingConfig& config) {
  const std::vector<double>& pose = config.predicted_pose;
  if (pose.size() != 7) {
    throw std::runtime_error("predicted_pose needs 7 numbers: tx ty tz qx qy qz qw");
  }
  const Eigen::Quaterniond rotation(pose[6], pose[3], pose[4], pose[5]);
  if (!(rotation.norm() > 0.0)) {
    throw std::runtime_error("predicted_pose: the quaternion qx qy qz qw is zero");
  }
  PoseWithCovariance predicted;
  predicted.pose = makePose({pose[0], pose[1], pose[2]}, rotation.normalized());
  predicted.covariance =
      diagonalPoseCovariance(config.predicted_position_sigma_m,
                             config.predicted_rotation_sigma_deg * std::numbers::pi / 180.0);
  return predicted;
}

TrackerOptions trackerOptionsOf(const OfflineTrackingConfig& config) {
  TrackerOptions options;
  if (config.sun_deg.empty()) {
    return options;
  }
  if (config.sun_deg.size() != 2) {
    throw std::runtime_error("sun needs 2 numbers: azimuth elevation (deg)");
  }
  options.localizer.visibility.sunlight =
      Sunlight::fromAzimuthElevation(config.sun_deg[0], config.sun_deg[1], config.ambient);
  return options;
}

}  // namespace

OfflineTrackingSummary runOfflineTracking(const OfflineTrackingConfig& config, std::ostream& out) {
  const std::optional<int> file_epsg =
      config.city_model_crs.empty()
          ? std::nullopt
          : std::optional<int>(citymodel::parseEpsgCode(config.city_model_crs));
  const LocalModel local = readLocalModel(config.city_model, siteOriginOf(config), file_epsg);
  out << fmt::format(
      "lineloc-track: {} buildings, {} lines, {} faces; frame = model CRS minus site origin "
      "({:.3f}, {:.3f}, {:.3f})\n",
      local.buildings, local.model.lines.size(), local.model.faces.size(), local.origin.x(),
      local.origin.y(), local.origin.z());
  const CameraCalibration calibration = readCameraCalibration(config.camera_calibration);
  ModelTracker tracker(local.model, calibration.camera, predictedPoseOf(config),
                       trackerOptionsOf(config));
  FeatureExtractor extractor(calibration, config.extractor);
  TumWriter trajectory(config.out);
  if (!config.overlay_dir.empty()) {
    std::filesystem::create_directories(config.overlay_dir);
  }
  OfflineTrackingSummary summary;
  const std::vector<FrameRef> frames = listImageSequence(config.images);
  for (const FrameRef& frame_ref : frames) {
    const cv::Mat image = cv::imread(frame_ref.path, cv::IMREAD_COLOR);
    if (image.empty()) {
      throw std::runtime_error(fmt::format("cannot read image '{}'", frame_ref.path));
    }
    const FrameFeatures& features = extractor.extract(image);
    const TrackedFrame frame = tracker.track(features.segments, features.corners);
    summary.aligned += frame.alignment.status == AlignmentStatus::kOk ? 1 : 0;
    spdlog::info("frame {}: {}{} ({} inliers){}", summary.frames, toString(frame.alignment.status),
                 frame.acquired ? " after a search" : "", frame.alignment.inliers,
                 frame.alignment.message.empty() ? "" : ": " + frame.alignment.message);
    trajectory.write({frame_ref.stamp_ns.value_or(summary.frames), frame.T_world_camera.pose});
    if (!config.overlay_dir.empty()) {
      cv::imwrite(fmt::format("{}/frame_{:06d}.png", config.overlay_dir, summary.frames),
                  drawTrackingOverlay(image, features.segments, frame, calibration));
    }
    ++summary.frames;
  }
  out << fmt::format("lineloc-track: {} frames, {} aligned; poses in {}\n", summary.frames,
                     summary.aligned, config.out);
  return summary;
}

}  // namespace lineloc
