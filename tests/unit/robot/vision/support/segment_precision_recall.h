// Precision and recall of detected line segments against labelled ones, by
// the two criteria of line-segment detection benchmarks. Both first clip the
// two sets to the labelled region and drop segments shorter than
// min_length_px there.
//
// Coverage (pixel-based; it does not care how a line is cut into pieces):
// each segment is sampled every sample_step_px along its length. A labelled
// sample is recalled when a detected segment passes within max_distance_px of
// it at an angle to its segment of at most max_angle_deg; a detected sample
// is correct when a labelled segment does, with the same tolerances. Then
//   recall = recalled labelled length / labelled length,
//   precision = correct detected length / detected length.
//
// Endpoints (structural; a segment counts only when cut where the label is):
// a detected segment matches a labelled one when each of its endpoints is
// within max_endpoint_distance_px of one endpoint of the labelled segment
// (either order). Matches are one to one, closest first (by the larger of the
// two endpoint distances). Then
//   recall = matched / labelled segments, precision = matched / detected segments.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace lineloc::testing {

struct Segment2d {
  Eigen::Vector2d start;
  Eigen::Vector2d end;
};

struct PrecisionRecall {
  double precision = 0.0;
  double recall = 0.0;
  int labelled_segments = 0;  // after clipping and the length limit
  int detected_segments = 0;
};

struct CoverageOptions {
  double max_distance_px = 3.0;
  double max_angle_deg = 5.0;
  double min_length_px = 20.0;
  double sample_step_px = 1.0;
};

struct CoverageScore : PrecisionRecall {
  double labelled_length_px = 0.0;  // after clipping and the length limit
  double detected_length_px = 0.0;
};

CoverageScore scoreCoverage(const std::vector<Segment2d>& labelled,
                            const std::vector<Segment2d>& detected,
                            const Eigen::AlignedBox2d& region, const CoverageOptions& options = {});

struct EndpointOptions {
  double max_endpoint_distance_px = 5.0;
  double min_length_px = 20.0;
};

struct EndpointScore : PrecisionRecall {
  int matched = 0;
};

EndpointScore scoreEndpoints(const std::vector<Segment2d>& labelled,
                             const std::vector<Segment2d>& detected,
                             const Eigen::AlignedBox2d& region,
                             const EndpointOptions& options = {});

}  // namespace lineloc::testing
