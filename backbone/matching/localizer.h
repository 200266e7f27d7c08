// One frame's pose from the model near the prior — the step the backbone
// service and the offline tracker share. A prior tight enough for gated
// matching (largest position sigma and yaw sigma under the tracking limits:
// the robot's prediction between fixes) is tracked: hidden-line removal from
// the prior (visible_lines.h) and alignment (model_alignment.h). A poorer one
// (a DGPS + compass start, a long outage) is acquired: searched, aligned and
// verified (pose_acquisition.h).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "backbone/matching/pose_acquisition.h"

namespace lineloc {

struct LocalizerOptions {
  double max_tracking_position_sigma_m = 0.2;
  double max_tracking_yaw_sigma_rad = 0.5 * M_PI / 180.0;
  VisibilityOptions visibility;
  AlignmentOptions alignment;
  AcquisitionOptions acquisition;
};

struct Localization {
  Alignment alignment;
  // Set when the pose was acquired by a search rather than tracked.
  std::optional<SearchSummary> search;
  // The model pieces visible from the prior (tracking) or from the winning
  // hypothesis (acquisition).
  std::vector<VisibleSegment> visible;
  int64_t visibility_ns = 0;
};

// True when `prior` is too poor for gated matching.
bool needsAcquisition(const PoseWithCovariance& prior, const LocalizerOptions& options);

Localization localize(const std::vector<ImageSegment>& image,
                      const std::vector<ModelSegment>& lines, const OcclusionScene& scene,
                      const PoseWithCovariance& prior, const PinholeCamera& camera,
                      const LocalizerOptions& options);

}  // namespace lineloc
