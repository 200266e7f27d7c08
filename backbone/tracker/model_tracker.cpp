#include "backbone/tracker/model_tracker.h"

#include <utility>

#include "backbone/tracker/scene_scale.h"

namespace lineloc {
namespace {

TrackedModel scaledModel(TrackedModel model, double factor) {
  for (ModelSegment& line : model.lines) {
    line.start_world *= factor;
    line.end_world *= factor;
    line.sigma_m *= factor;
  }
  for (FaceRing& face : model.faces) {
    for (Eigen::Vector3d& point : face) {
      point *= factor;
    }
  }
  return model;
}

void scaleFrame(TrackedFrame& frame, double factor) {
  frame.alignment.T_world_camera = scaledWorld(frame.alignment.T_world_camera, factor);
  frame.alignment.next_gate = scaledWorld(frame.alignment.next_gate, factor);
  frame.T_world_camera = scaledWorld(frame.T_world_camera, factor);
  for (VisibleSegment& line : frame.visible) {
    line.start_world *= factor;
    line.end_world *= factor;
    line.sigma_m *= factor;
  }
}

}  // namespace

ModelTracker::ModelTracker(TrackedModel model, const PinholeCamera& camera,
                           const PoseWithCovariance& start, const TrackerOptions& options)
    : metres_per_unit_(
          options.scale_to_scene
              ? sceneMetresPerUnit(OcclusionScene(model.faces, model.face_building_ids), camera,
                                   start.pose, options.street_depth_m)
              : 1.0),
      model_(scaledModel(std::move(model), 1.0 / metres_per_unit_)),
      scene_(model_.faces, model_.face_building_ids),
      camera_(camera),
      options_(options),
      current_(scaledWorld(start, 1.0 / metres_per_unit_)) {}

TrackedFrame ModelTracker::track(const std::vector<ImageSegment>& segments,
                                 const std::vector<ImageCorner>& corners) {
  PoseWithCovariance predicted = motion_ ? composeExactMotion(current_, *motion_) : current_;
  if (!first_frame_) {
    predicted.covariance += diagonalPoseCovariance(options_.process_position_sigma_m,
                                                   options_.process_rotation_sigma_rad);
  }
  first_frame_ = false;
  if (last_ok_) {
    predicted = narrowedForTracking(predicted, options_.localizer);
  }
  Localization localization =
      localize(segments, corners, model_.lines, scene_, predicted, camera_, options_.localizer);
  TrackedFrame frame;
  frame.acquired = localization.search.has_value();
  if (frame.acquired && localization.alignment.status == AlignmentStatus::kOk) {
    Localization refined =
        localize(segments, corners, model_.lines, scene_,
                 narrowedForTracking(localization.alignment.T_world_camera, options_.localizer),
                 camera_, options_.localizer);
    if (refined.alignment.status == AlignmentStatus::kOk) {
      localization = std::move(refined);
    }
  }
  frame.alignment = std::move(localization.alignment);
  frame.visible = std::move(localization.visible);
  const bool ok = frame.alignment.status == AlignmentStatus::kOk;
  frame.T_world_camera = ok ? frame.alignment.T_world_camera : predicted;
  if (ok && last_ok_) {
    motion_ = current_.pose.inverse() * frame.T_world_camera.pose;
    motion_->linear() = Eigen::Quaterniond(motion_->linear()).normalized().toRotationMatrix();
  }
  current_ = frame.T_world_camera;
  last_ok_ = ok;
  scaleFrame(frame, metres_per_unit_);
  return frame;
}

}  // namespace lineloc
