// Model-based tracking without DDS or a database: the backbone's localizer
// (hidden-line removal and alignment, or acquisition when the prior is poor)
// runs frame after frame on a city model held in memory, each frame predicted
// from the last with a constant-position motion model whose covariance grows
// by the process noise Q per frame (P_predicted = P + Q). A frame whose
// alignment fails keeps the prediction, so the covariance keeps growing until
// the localizer searches for the model and finds it again.
#pragma once

#include <vector>

#include "backbone/matching/localizer.h"

namespace lineloc {

struct TrackedModel {
  std::vector<ModelSegment> lines;
  std::vector<FaceRing> faces;
  std::vector<int64_t> face_building_ids;  // one per face, or empty: one building
};

struct TrackerOptions {
  LocalizerOptions localizer;
  // Process noise per frame (standard deviations).
  double process_position_sigma_m = 0.08;
  double process_rotation_sigma_rad = 0.3 * M_PI / 180.0;
};

struct TrackedFrame {
  Alignment alignment;
  bool acquired = false;
  // The aligned pose when alignment.status is kOk, else the prediction.
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

 private:
  TrackedModel model_;
  OcclusionScene scene_;
  PinholeCamera camera_;
  TrackerOptions options_;
  PoseWithCovariance current_;
};

}  // namespace lineloc
