// Scores detected segments and corners against a synthetic scene's truth.
//
// A detected segment lies on a true one when both its endpoints are within
// max_distance of the true line and within its extent (+ max_distance), and
// the angles differ by at most max_angle. A true segment is found when one
// detected segment on it covers at least min_coverage of its length; its
// errors are those of the detected segment that covers it most: endpoint
// error = distance of each detected endpoint to the true endpoint nearest it.
#pragma once

#include <vector>

#include "common/messages/messages.h"
#include "synthetic_scene.h"

namespace lineloc::testing {

struct SegmentScore {
  int true_segments = 0;  // longer than min_length
  int found = 0;
  int detected = 0;  // longer than min_length
  int spurious = 0;  // detected on no true segment
  double max_endpoint_error_px = 0.0;
  double max_angle_error_deg = 0.0;
  std::vector<double> endpoint_errors_px;
  std::vector<double> angle_errors_deg;
  double recall() const { return true_segments ? double(found) / true_segments : 0.0; }
  double spuriousRate() const { return detected ? double(spurious) / detected : 0.0; }
};

struct ScoringOptions {
  double min_length_px = 20.0;
  double max_distance_px = 1.5;
  double max_angle_deg = 2.0;
  double min_coverage = 0.8;
};

SegmentScore scoreSegments(const SyntheticScene& scene, const std::vector<ImageSegment>& detected,
                           const ScoringOptions& options = {});

struct CornerScore {
  int true_corners = 0;
  int found = 0;  // a detected corner within max_distance
  std::vector<double> errors_px;
  double max_error_px = 0.0;
};

CornerScore scoreCorners(const SyntheticScene& scene, const std::vector<ImageCorner>& detected,
                         double max_distance_px = 2.0);

}  // namespace lineloc::testing
