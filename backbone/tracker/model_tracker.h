// Model-based tracking without DDS or a database: the backbone's localizer
// (hidden-line removal and alignment, or acquisition when the prior is poor)
// runs frame after frame on a city model held in memory.
//
// Each frame is predicted from the last with a constant-velocity model: the
// motion between the last two OK answers, T_k-1^-1 T_k, applied again
// (composeExactMotion), or none before there are two; its covariance grows by
// the process noise Q per frame (P_predicted = P + Q). The first frame's
// prediction is the start itself. After an OK answer the prediction is
// narrowed to the localizer's tracking limits where it exceeds them
// (narrowedForTracking): an answer's covariance is conservative (jackknife,
// confidence scale, rivals) and Q bounds the motion, so a camera that was
// found is tracked, not searched for again. A frame whose alignment fails
// keeps the prediction, so the covariance keeps growing until the localizer
// searches for the model and finds it again; a pose a search found is then
// aligned once more as tracking aligns, from itself narrowed to the limits,
// which the search's wide loss leaves to it.
//
// Asked to, the tracker works in scene units (scene_scale.h), fixed from the
// start pose, so that the localizer's lengths and the process noise hold for
// a model of any size seen from any distance; it takes and answers poses,
// covariances and visible lines in the model's metres either way.
#pragma once

#include <optional>
#include <vector>

#include "backbone/matching/localizer.h"

namespace lineloc {

struct TrackedModel {
  std::vector<ModelSegment> lines;
  std::vector<FaceRing> faces;
  std::vector<int64_t> face_building_ids;  // one per face, or empty: one building
};

struct TrackerOptions {
  // Lengths here and in the localizer are set for street views, whose
  // surfaces a camera sees at a median depth of street_depth_m (on simulated
  // drives). With scale_to_scene they are in scene units (scene_scale.h),
  // which a model of an object needs; without, in metres, a city model's.
  LocalizerOptions localizer;
  bool scale_to_scene = false;
  double street_depth_m = 12.0;
  // Process noise per frame (standard deviations).
  double process_position_sigma_m = 0.08;
  double process_rotation_sigma_rad = 0.3 * M_PI / 180.0;
};

struct TrackedFrame {
  Alignment alignment;
  bool acquired = false;
  // The aligned pose when alignment.status is kOk, else the prediction (m).
  PoseWithCovariance T_world_camera;
  std::vector<VisibleSegment> visible;
};

class ModelTracker {
 public:
  ModelTracker(TrackedModel model, const PinholeCamera& camera, const PoseWithCovariance& start,
               const TrackerOptions& options);

  // One image's segments and Förstner corners (undistorted pixels).
  TrackedFrame track(const std::vector<ImageSegment>& segments,
                     const std::vector<ImageCorner>& corners);

  // Metres per scene unit.
  double metresPerUnit() const { return metres_per_unit_; }

 private:
  double metres_per_unit_;
  TrackedModel model_;
  OcclusionScene scene_;
  PinholeCamera camera_;
  TrackerOptions options_;
  PoseWithCovariance current_;
  bool last_ok_ = false;
  bool first_frame_ = true;
  std::optional<Eigen::Isometry3d> motion_;
};

}  // namespace lineloc
