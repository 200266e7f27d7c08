// Split-and-merge polygonal approximation of an edge chain (Persa & Jonker §3;
// Pavlidis & Horowitz 1974).
//
// Split: a piece whose farthest point lies more than split_distance from the
// chord joining its end points is split there, recursively; the split point,
// usually the corner itself, joins neither piece. Merge: two adjacent pieces
// become one when every point of their union lies within split_distance of
// the union's total-least-squares line. Pieces keep the chain's order.
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "robot/vision/edges/edge_linker.h"
#include "robot/vision/lines/line_moments.h"

namespace lineloc {

class SplitAndMerge {
 public:
  // Throws std::invalid_argument unless split_distance_px > 0 and min_points >= 3.
  SplitAndMerge(double split_distance_px, int min_points);

  // Appends to `pieces` the straight pieces of the polyline `points`, as index
  // ranges into it; pieces of fewer than min_points points are dropped.
  void approximate(std::span<const Eigen::Vector2f> points, std::vector<PointRange>& pieces);
  // The same with the polyline's cumulativeMoments at hand.
  void approximate(std::span<const Eigen::Vector2f> points, std::span<const PointMoments> prefix,
                   std::vector<PointRange>& pieces);

 private:
  void split(std::span<const Eigen::Vector2f> points);
  void merge(std::span<const Eigen::Vector2f> points, std::span<const PointMoments> prefix);
  bool fitsOneLine(std::span<const Eigen::Vector2f> points, std::span<const PointMoments> prefix,
                   PointRange range) const;

  double split_distance_px_;
  int min_points_;
  std::vector<PointRange> stack_;
  std::vector<PointRange> pieces_;
  std::vector<PointMoments> prefix_;  // for the overload without
};

}  // namespace lineloc
