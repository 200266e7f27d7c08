#include "backbone/tracker/model_tracker.h"

#include <utility>

namespace lineloc {

ModelTracker::ModelTracker(TrackedModel model, const PinholeCamera& camera,
                           const PoseWithCovariance& start, const TrackerOptions& options)
    : model_(std::move(model)),
      scene_(model_.faces, model_.face_building_ids),
      camera_(camera),
      options_(options),
      current_(start) {}

TrackedFrame ModelTracker::track(const std::vector<ImageSegment>& segments,
                                 const std::vector<ImageCorner>& corners) {
  PoseWithCovariance predicted = current_;
  predicted.covariance += diagonalPoseCovariance(options_.process_position_sigma_m,
                                                 options_.process_rotation_sigma_rad);
  TrackedFrame frame;
  Localization localization =
      localize(segments, corners, model_.lines, scene_, predicted, camera_, options_.localizer);
  frame.alignment = std::move(localization.alignment);
  frame.acquired = localization.search.has_value();
  frame.visible = std::move(localization.visible);
  frame.T_world_camera =
      frame.alignment.status == AlignmentStatus::kOk ? frame.alignment.T_world_camera : predicted;
  current_ = frame.T_world_camera;
  return frame;
}

}  // namespace lineloc
