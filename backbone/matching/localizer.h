// One frame's pose from the model near the prior — the step the backbone
// service and the offline tracker share. A prior tight enough for gated
// matching (largest position sigma and yaw sigma under the tracking limits:
// the robot's prediction between fixes) is tracked: hidden-line removal from
// the prior (visible_lines.h) and alignment (model_alignment.h). A poorer one
// (a DGPS + compass start, a long outage) is acquired: searched, aligned and
// verified (pose_acquisition.h).
//
// Tracking first trusts the prediction's centre: it aligns with the prior's
// covariance scaled by first_gate_scale^2, so the first round gates each model
// line within a few pixels of where the prediction puts it, and falls back to
// the whole covariance only when that alignment is not OK. The prediction
// after a fix carries the fix's covariance, which the jackknife makes
// conservative (model_alignment.h); gates that wide hold two model lines for
// many true building edges, which the alignment then leaves out as ambiguous,
// while the window frames beside the edges, each near one model line only,
// stay in and pull the pose. On a Delft frame (tests/integration/drive) the
// wide first round kept 15 true edges and 16 window edges and ended 0.5 m off
// with a 5 cm sigma; the narrow one kept 29 true and 4 others and ended 1 cm
// off.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "backbone/matching/pose_acquisition.h"

namespace lineloc {

struct LocalizerOptions {
  double max_tracking_position_sigma_m = 0.2;
  double max_tracking_yaw_sigma_rad = 0.5 * M_PI / 180.0;
  // Scale of the prior's standard deviations for tracking's first alignment.
  double first_gate_scale = 0.1;
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
