// Correspondences between the corners of the predicted view (model vertices,
// visible_corners.h) and the Förstner corners the robot found, gated by the
// predicted pose's uncertainty as line_matcher.h gates lines: a model corner
// projected with the pose to u, with covariance Sigma_u = J Sigma J^T
// (projectPoint), matches an image corner q of covariance Sigma_q when
//   chi^2 = (q - u)^T (Sigma_u + Sigma_q + floor^2 I)^-1 (q - u) <= gate_chi2.
// Window corners crowd a façade: a model corner is matched only when its best
// image corner beats the second by ambiguity_margin_chi2, and an image corner
// that is the best of two model corners is matched with neither.
#pragma once

#include <vector>

#include "backbone/visibility/visible_corners.h"
#include "common/camera/camera_calibration.h"
#include "common/geometry/pose.h"
#include "common/messages/messages.h"

namespace lineloc {

struct CornerMatchingOptions {
  // chi^2 with 2 degrees of freedom: 13.82 keeps 99.9 % of true matches.
  double gate_chi2 = 13.82;
  // Floor on the model corner's projected sigma (pixels), as for lines
  // (MatchingOptions::model_sigma_floor_px).
  double model_sigma_floor_px = 1.0;
  double ambiguity_margin_chi2 = 2.0;
};

struct CornerMatch {
  int image_index = 0;
  int model_index = 0;
  double chi2 = 0.0;
};

// One-to-one, unambiguous matches, in the order of the model corners.
std::vector<CornerMatch> matchCorners(const std::vector<ImageCorner>& image,
                                      const std::vector<VisibleCorner>& model,
                                      const PoseWithCovariance& T_world_camera,
                                      const PinholeCamera& camera,
                                      const CornerMatchingOptions& options);

}  // namespace lineloc
