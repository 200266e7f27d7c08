// Links edge points into chains of 8-connected neighbours (Persa & Jonker §3:
// the edges that split-and-merge approximates by straight lines).
//
// Edge points come linked to their neighbours along the edge
// (EdgeDetector::next(), ::previous(), see edge_detector.h), so that chains stop at
// corners, polarity flips and junctions. Chains follow the links from each
// point without a predecessor (closed contours from any point); chains
// shorter than min_points are dropped.
#pragma once

#include <cstdint>
#include <vector>

namespace lineloc {

// Points [begin, end) of EdgeLinker::chainPoints().
struct PointRange {
  int begin;
  int end;
  int size() const { return end - begin; }
};

struct EdgeLinkerOptions {
  int min_points = 8;
};

class EdgeLinker {
 public:
  // Throws std::invalid_argument for min_points < 2.
  explicit EdgeLinker(const EdgeLinkerOptions& options);

  // `next`, `previous`: each point's linked neighbours, as EdgeDetector finds them.
  void link(const std::vector<int32_t>& next, const std::vector<int32_t>& previous);

  // Indices into `points`, chain after chain, each from its first point
  // along +t.
  const std::vector<int32_t>& chainPoints() const { return chain_points_; }
  const std::vector<PointRange>& chains() const { return chains_; }

 private:
  void addChain(const std::vector<int32_t>& next, int32_t first);

  EdgeLinkerOptions options_;
  std::vector<uint8_t> visited_;
  std::vector<int32_t> chain_points_;
  std::vector<PointRange> chains_;
};

}  // namespace lineloc
