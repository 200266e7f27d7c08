// Merges collinear segments separated by small gaps, such as a building edge
// cut by a pole or a tree (Persa & Jonker §3: broken lines are one model line).
//
// Two segments join when their angles differ by at most max_angle, their
// gradients point the same way (same polarity), each one's endpoints lie
// within max_distance of the other's line, and the gap between them along the
// line is at most min(max_gap, max_gap_ratio x shorter length) — the ratio
// keeps a row of window edges from fusing into one false line. Joined groups
// (union-find over pairs found by a sweep over angle) are refitted by total
// least squares from their summed moments.
#pragma once

#include <cstdint>
#include <vector>

#include "robot/vision/lines/line_segment.h"

namespace lineloc {

struct CollinearMergeOptions {
  double max_angle_rad = 0.035;
  double max_distance_px = 1.0;
  double max_gap_px = 25.0;
  double max_gap_ratio = 0.25;
};

class CollinearMerger {
 public:
  explicit CollinearMerger(const CollinearMergeOptions& options);

  // Replaces `segments` by the merged set (order not kept).
  void merge(std::vector<LineSegment>& segments, const LineFitOptions& fit_options);

 private:
  // A segment as joinable() needs it.
  struct Extent {
    double angle;  // of the direction, in [0, pi)
    Eigen::Vector2d centroid, direction, normal, start, end, gradient_sum;
    double start_along, end_along;
    int32_t segment;
  };

  bool joinable(const Extent& a, const Extent& b) const;
  int32_t root(int32_t i);
  void findGroups(const std::vector<LineSegment>& segments);

  CollinearMergeOptions options_;
  std::vector<Extent> by_angle_;
  std::vector<int32_t> parent_;
  std::vector<LineSegment> originals_;
};

}  // namespace lineloc
