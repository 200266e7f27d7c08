// Block matching for motion estimation, Persa & Jonker §4: each block of the
// reference frame is compared, by its SAD (eq. 7), with the displaced blocks
// of the current frame inside a window of +-R pixels, and the displacement of
// least SAD is its motion vector.
//
// Strategies: full search (every displacement; optionally with early
// termination: a spiral from the zero vector whose partial SADs, 4 rows at a
// time, stop once they exceed the best so far; same result as full search),
// three-step search (Koga et al. 1981: 3x3 pattern, step halved from
// 2^ceil(log2(R+1)-1) to 1) and diamond search (Zhu & Ma 2000: large diamond
// until its centre wins, then the small diamond).
//
// Ties between equal SADs go to the shorter vector (dx^2 + dy^2), then to the
// smaller dy, then dx (candidate_rank.h), so every strategy and SIMD path
// agrees on the result. Full search of grey 8 or 16 pixel blocks runs the
// SIMD path's grid search (sad_kernels.h), one call per frame pair, with or
// without early termination: the grid search computes a candidate's SAD for
// several blocks and candidates per instruction stream, faster than the
// per-candidate partial sums and bound tests could skip work, and the
// result is the same.
//
// Sub-pixel refinement fits a parabola through the SADs at -1, 0, +1 along
// each axis: offset = (c_- - c_+) / (2 (c_- - 2 c_0 + c_+)), in [-1/2, 1/2].
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "robot/vision/block_matching/sad_kernels.h"

namespace lineloc {

enum class SearchStrategy { kFull, kFullEarlyTermination, kThreeStep, kDiamond };

struct BlockMatchingOptions {
  int block_width_px = 16;
  int block_height_px = 16;
  int search_radius_px = 16;  // R, at most kMaxSearchRadiusPx
  SearchStrategy strategy = SearchStrategy::kFull;
};

enum class MatchStatus {
  kMatched,           // minimum inside the window, sub-pixel refined on both axes
  kAtSearchBoundary,  // minimum on the window's edge: the true one may lie outside
  kTextureless,       // the SAD does not rise around the minimum: ambiguous
};

// The block at (x, y) of the reference frame is found at (x + dx, y + dy) of
// the current frame.
struct BlockMatch {
  int x = 0;
  int y = 0;
  int dx = 0;
  int dy = 0;
  uint32_t sad = 0;
  float subpixel_dx = 0.0f;  // dx + parabola offset (dx itself when not refined)
  float subpixel_dy = 0.0f;
  MatchStatus status = MatchStatus::kMatched;
};

class BlockMatcher {
 public:
  // Throws std::invalid_argument for block sizes < 1 or a radius outside
  // [0, kMaxSearchRadiusPx], or an unsupported SIMD path.
  explicit BlockMatcher(const BlockMatchingOptions& options, SimdPath path = bestSimdPath());

  // Matches every whole block of a grid with the block size as its step.
  // Frames: same size and type, CV_8UC1 or CV_8UC3 (SAD over all channels);
  // throws std::invalid_argument naming the problem otherwise (empty, sizes
  // differ, block larger than the image).
  std::vector<BlockMatch> matchGrid(const cv::Mat& reference, const cv::Mat& current) const;

  // Matches the one block with top-left (x, y), which must lie in the image.
  BlockMatch matchBlock(const cv::Mat& reference, const cv::Mat& current, int x, int y) const;

  const BlockMatchingOptions& options() const { return options_; }

 private:
  class Search;

  void validateFrames(const cv::Mat& reference, const cv::Mat& current) const;
  // Full search of grey blocks the SadKernels grid search takes.
  bool usesGridSearch(const cv::Mat& frame) const;

  BlockMatchingOptions options_;
  const SadKernels* kernels_;
};

}  // namespace lineloc
