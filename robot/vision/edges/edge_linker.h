// Links edge points into chains of 8-connected neighbours (Persa & Jonker §3:
// the edges that split-and-merge approximates by straight lines).
//
// From each unvisited point the chain grows both ways along the edge tangent
// t = (-gy, gx) / |g|: the next point is the unvisited 8-neighbour whose step
// s makes the smallest angle with the walking direction (s.t > 0 required)
// and whose gradient turns by at most max_turn from the current one
// (g1.g2 >= cos(max_turn) |g1| |g2|), so a chain stops at corners, at
// polarity flips and at junctions. Chains shorter than min_points are dropped.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "robot/vision/edges/edge_detector.h"

namespace lineloc {

// Points [begin, end) of EdgeLinker::chainPoints().
struct PointRange {
  int begin;
  int end;
  int size() const { return end - begin; }
};

struct EdgeLinkerOptions {
  double max_turn_rad = 0.3;  // largest gradient turn between linked neighbours
  int min_points = 8;
};

class EdgeLinker {
 public:
  // Throws std::invalid_argument for a turn outside (0, pi) or min_points < 2.
  explicit EdgeLinker(const EdgeLinkerOptions& options);

  // `point_index`: CV_32S map of pixel -> index in `points` or -1, with no
  // point within 1 px of the border (as EdgeDetector makes it).
  void link(const std::vector<EdgePoint>& points, const cv::Mat& point_index);

  // Indices into `points`, chain after chain, each in walking order.
  const std::vector<int32_t>& chainPoints() const { return chain_points_; }
  const std::vector<PointRange>& chains() const { return chains_; }

 private:
  void walk(int32_t start, float direction_sign, std::vector<int32_t>& out);

  EdgeLinkerOptions options_;
  float cos_max_turn_;
  const std::vector<EdgePoint>* points_ = nullptr;
  const cv::Mat* point_index_ = nullptr;
  std::vector<uint8_t> visited_;
  std::vector<int32_t> backward_;
  std::vector<int32_t> chain_points_;
  std::vector<PointRange> chains_;
};

}  // namespace lineloc
