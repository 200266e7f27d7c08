// Links edge points into chains of 8-connected neighbours (Persa & Jonker §3:
// the edges that split-and-merge approximates by straight lines).
//
// Every edge point p knows the nearest edge points ahead of and behind it
// along its tangent (EdgePoint::ahead, ::behind). p and q are linked when q
// is ahead of p, p is behind q, and the gradient turns by at most max_turn
// between them (g1.g2 >= cos(max_turn) |g1| |g2|), as in the chaining of the
// Canny/Devernay detector (von Gioi & Randall, IPOL 2017): a chain stops at
// corners, at polarity flips and at junctions, and runs through both pixels
// where non-maximum suppression leaves a staircase two pixels wide. Chains
// follow the links from a point without predecessor (closed contours from any
// point); chains shorter than min_points are dropped.
#pragma once

#include <cstdint>
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

  // `points` with their neighbours, as EdgeDetector finds them.
  void link(const std::vector<EdgePoint>& points);

  // Indices into `points`, chain after chain, each from its first point
  // along +t.
  const std::vector<int32_t>& chainPoints() const { return chain_points_; }
  const std::vector<PointRange>& chains() const { return chains_; }

 private:
  void addChain(int32_t first);

  EdgeLinkerOptions options_;
  float cos_max_turn_;
  std::vector<int32_t> next_, previous_;
  std::vector<uint8_t> visited_;
  std::vector<int32_t> chain_points_;
  std::vector<PointRange> chains_;
};

}  // namespace lineloc
