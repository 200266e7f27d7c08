#include "apps/offline_tracking.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <ostream>

#include "backbone/tracker/model_file.h"
#include "backbone/tracker/model_tracker.h"
#include "backbone/tracker/tracking_overlay.h"
#include "common/camera/camera_calibration.h"
#include "common/config/option_values.h"
#include "common/image/image_file.h"
#include "common/trajectory/fix_log.h"
#include "common/trajectory/tum_trajectory.h"
#include "db/citymodel/city_model.h"
#include "robot/input/image_sequence.h"

namespace lineloc {
namespace {

citymodel::UpAxis upAxisOption(const std::string& axis) {
  try {
    return citymodel::parseUpAxis(axis);
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(fmt::format("model_up_axis: {}", error.what()));
  }
}

TrackerOptions trackerOptionsOf(const OfflineTrackingConfig& config, bool local_frame) {
  TrackerOptions options;
  options.localizer.visibility.sunlight = driveSun(config.drive);
  // A model in its own frame is an object's, of any size: tracked in scene
  // units, and with no terrain to take its base from, its foot as exact as
  // the rest of it.
  options.scale_to_scene = local_frame;
  if (local_frame) {
    options.localizer.alignment.ground_line_sigma_m = options.localizer.alignment.model_sigma_m;
    options.localizer.acquisition.alignment.ground_line_sigma_m =
        options.localizer.acquisition.alignment.model_sigma_m;
  }
  return options;
}

}  // namespace

OfflineTrackingSummary runOfflineTracking(const OfflineTrackingConfig& config, std::ostream& out) {
  const LocalModel local = readDriveModel(config.drive, upAxisOption(config.model_up_axis));
  out << fmt::format(
      "lineloc-track: {} buildings, {} lines, {} faces; frame = model {} minus site origin "
      "({:.3f}, {:.3f}, {:.3f})\n",
      local.buildings, local.model.lines.size(), local.model.faces.size(),
      local.local_frame ? "frame" : "CRS", local.origin.x(), local.origin.y(), local.origin.z());
  const CameraCalibration calibration = readCameraCalibration(config.drive.camera_calibration);
  const PoseWithCovariance predicted_T_model_camera =
      poseOption(config.predicted_pose, config.predicted_position_sigma_m,
                 config.predicted_rotation_sigma_deg, "predicted_pose");
  ModelTracker tracker(local.model, calibration.camera,
                       changeWorldFrame(local.T_model_local.inverse(), predicted_T_model_camera),
                       trackerOptionsOf(config, local.local_frame));
  out << fmt::format("lineloc-track: tracking in units of {:.4g} m (scene scale)\n",
                     tracker.metresPerUnit());
  FeatureExtractor extractor(calibration, config.extractor);
  TumWriter trajectory(config.out);
  std::optional<FixLogWriter> fix_log;
  if (!config.fix_log_out.empty()) {
    fix_log.emplace(config.fix_log_out);
  }
  if (!config.overlay_dir.empty()) {
    std::filesystem::create_directories(config.overlay_dir);
  }
  OfflineTrackingSummary summary;
  const std::vector<FrameRef> frames = listImageSequence(config.drive.images);
  for (const FrameRef& frame_ref : frames) {
    const cv::Mat image = readImageFile(frame_ref.path, cv::IMREAD_COLOR);
    const FrameFeatures& features = extractor.extract(image);
    const TrackedFrame frame = tracker.track(features.segments, features.corners);
    summary.aligned += frame.alignment.status == AlignmentStatus::kOk ? 1 : 0;
    spdlog::info("frame {}: {}{} ({} inliers){}", summary.frames, toString(frame.alignment.status),
                 frame.acquired ? " after a search" : "", frame.alignment.inliers,
                 frame.alignment.message.empty() ? "" : ": " + frame.alignment.message);
    const int64_t stamp_ns = frame_ref.stamp_ns.value_or(summary.frames);
    const PoseWithCovariance T_model_camera =
        changeWorldFrame(local.T_model_local, frame.T_world_camera);
    trajectory.write({stamp_ns, T_model_camera.pose});
    if (fix_log) {
      LoggedFix fix;
      fix.stamp_ns = stamp_ns;
      fix.T_world_camera = T_model_camera;
      fix.status = toString(frame.alignment.status);
      fix.inliers = static_cast<uint32_t>(frame.alignment.inliers);
      fix.model_lines = static_cast<uint32_t>(frame.visible.size());
      fix.residual_rms_px = frame.alignment.rms_residual_px;
      fix_log->write(fix);
    }
    if (!config.overlay_dir.empty()) {
      cv::imwrite(
          fmt::format("{}/frame_{:06d}.png", config.overlay_dir, summary.frames),
          drawTrackingOverlay(image, features.segments, features.corners, frame, calibration));
    }
    ++summary.frames;
  }
  out << fmt::format("lineloc-track: {} frames, {} aligned; poses in {}\n", summary.frames,
                     summary.aligned, config.out);
  return summary;
}

}  // namespace lineloc
