// Straight line segments from edge chains (Persa & Jonker §3): edge points
// undistorted through the lookup table, split-and-merge of every chain, a
// total-least-squares refit of every piece after trimming the end points that
// bend away near a corner (farther than trim_distance from the line through
// the piece's core, its points more than trim_margin from its ends, which
// the bend does not reach), collinear pieces merged across small gaps,
// segments whose contrast the image's noise explains dropped (a contrario,
// segment_validation.h), endpoints that meet at a corner snapped to the
// intersection of their lines, and then short segments dropped (a segment cut
// short by the blur at a corner counts with the length it has when snapped).
#pragma once

#include <span>
#include <vector>

#include "robot/vision/edges/edge_detector.h"
#include "robot/vision/edges/edge_linker.h"
#include "robot/vision/edges/undistortion_table.h"
#include "robot/vision/lines/collinear_merger.h"
#include "robot/vision/lines/endpoint_snapper.h"
#include "robot/vision/lines/line_segment.h"
#include "robot/vision/lines/segment_validation.h"
#include "robot/vision/lines/split_and_merge.h"

namespace lineloc {

struct LineExtractorOptions {
  double split_distance_px = 1.0;
  double trim_distance_px = 0.25;  // end points farther from the core's line are dropped,
  double trim_sigmas = 3.0;        // or farther than this many of its residual sigmas
  double trim_margin_px = 3.0;     // the core leaves out this much at each end
  int min_points = 6;              // edge points per split-and-merge piece
  double min_length_px = 20.0;
  // Shorter pieces take no part in snapping; longer ones may reach
  // min_length_px by it: a side blurred short at both corners (2..4 px each).
  double min_snap_length_px = 12.0;
  double max_false_alarms = 1.0;  // epsilon of the a contrario test
  double min_contrast = 0.0;      // mean grey-level step, a floor besides the test
  int max_segments = 1024;        // the longest are kept
  LineFitOptions fit;
  CollinearMergeOptions merge;
  EndpointSnapOptions snap;
};

class LineExtractor {
 public:
  // Throws std::invalid_argument for out-of-range options.
  explicit LineExtractor(const LineExtractorOptions& options);

  // Segments in undistorted pixel coordinates, longest first, from the edge
  // points of an image of `image_size` whose measurements carry `noise`.
  void extract(const std::vector<EdgePoint>& points, const EdgeLinker& chains,
               const UndistortionTable& undistortion, cv::Size image_size, const EdgeNoise& noise);

  const std::vector<LineSegment>& segments() const { return segments_; }
  // Segments of the last image long enough to keep that the a contrario
  // test or min_contrast dropped.
  int rejectedSegments() const { return rejected_segments_; }
  // Where segment endpoints met at a corner (see EndpointSnapper).
  const std::vector<Junction>& junctions() const { return snapper_.junctions(); }

 private:
  void fitPieces(const std::vector<EdgePoint>& points, const std::vector<int32_t>& chain_points,
                 PointRange chain);
  void trimEnds(std::span<const Eigen::Vector2f> polyline, PointRange& piece) const;
  LineFit coreLine(std::span<const Eigen::Vector2f> polyline, PointRange piece) const;
  // Moments of a run of the current chain's points.
  PointMoments momentsOf(PointRange run) const;
  // Drops segments shorter than min_length_px, then those `validation`
  // finds meaningless or weaker than min_contrast, counted in rejected_segments_.
  void keepSignificant(double min_length_px, const SegmentValidation& validation);
  // Snaps endpoints at corners among the segments long enough once snapped.
  void snapEndpoints();

  LineExtractorOptions options_;
  SplitAndMerge split_and_merge_;
  CollinearMerger merger_;
  EndpointSnapper snapper_;
  std::vector<Eigen::Vector2f> undistorted_;
  std::vector<PointRange> pieces_;
  std::vector<PointMoments> prefix_;  // cumulativeMoments of the current chain
  std::vector<LineSegment> segments_;
  std::vector<LineSegment> unsnapped_;  // segments_ before the first snap
  int rejected_segments_ = 0;
};

}  // namespace lineloc
