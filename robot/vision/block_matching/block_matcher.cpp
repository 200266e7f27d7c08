#include "robot/vision/block_matching/block_matcher.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <stdexcept>

#include "robot/vision/block_matching/parabola_fit.h"

namespace lineloc {
namespace {

constexpr int kEarlyTerminationRows = 4;
constexpr int kRowAlignmentBytes = 64;

int roundUp(int value, int multiple) {
  return (value + multiple - 1) / multiple * multiple;
}

// `frame` (grey) with at least `margin_bytes` zeros on both sides of every
// row, rows starting 64-byte aligned: the grid search's view of a frame.
cv::Mat withMargins(const cv::Mat& frame, int margin_bytes) {
  const int left = roundUp(margin_bytes, kRowAlignmentBytes);
  const int right =
      roundUp(left + frame.cols + margin_bytes, kRowAlignmentBytes) - left - frame.cols;
  cv::Mat padded;
  cv::copyMakeBorder(frame, padded, 0, 0, left, right, cv::BORDER_CONSTANT, cv::Scalar(0));
  return padded(cv::Rect(left, 0, frame.cols, frame.rows));
}

}  // namespace

// The search of one block: its window clipped to the image and its SADs.
class BlockMatcher::Search {
 public:
  Search(const BlockMatcher& matcher, const cv::Mat& reference, const cv::Mat& current, int x,
         int y)
      : options_(matcher.options_),
        kernels_(*matcher.kernels_),
        channels_(reference.channels()),
        width_bytes_(options_.block_width_px * channels_),
        block_(reference.ptr<uint8_t>(y) + x * channels_),
        block_stride_(static_cast<ptrdiff_t>(reference.step)),
        origin_(current.ptr<uint8_t>(y) + x * channels_),
        stride_(static_cast<ptrdiff_t>(current.step)),
        dx_min_(std::max(-options_.search_radius_px, -x)),
        dx_max_(std::min(options_.search_radius_px, current.cols - options_.block_width_px - x)),
        dy_min_(std::max(-options_.search_radius_px, -y)),
        dy_max_(std::min(options_.search_radius_px, current.rows - options_.block_height_px - y)) {
    best_.x = x;
    best_.y = y;
  }

  // Refines the winner of a grid search.
  BlockMatch refine(const BlockBest& winner) {
    best_.dx = winner.dx;
    best_.dy = winner.dy;
    best_.sad = winner.sad;
    refine();
    return best_;
  }

  BlockMatch run() {
    switch (options_.strategy) {
      case SearchStrategy::kFull:
        fullSearch();
        break;
      case SearchStrategy::kFullEarlyTermination:
        spiralSearch();
        break;
      case SearchStrategy::kThreeStep:
        threeStepSearch();
        break;
      case SearchStrategy::kDiamond:
        diamondSearch();
        break;
    }
    refine();
    return best_;
  }

 private:
  bool inWindow(int dx, int dy) const {
    return dx >= dx_min_ && dx <= dx_max_ && dy >= dy_min_ && dy <= dy_max_;
  }

  const uint8_t* candidate(int dx, int dy) const { return origin_ + dy * stride_ + dx * channels_; }

  uint32_t sadAt(int dx, int dy) const {
    const uint8_t* b = candidate(dx, dy);
    if (channels_ == 1 && options_.block_width_px == 16 && options_.block_height_px == 16) {
      return kernels_.sad16x16(block_, block_stride_, b, stride_);
    }
    if (channels_ == 1 && options_.block_width_px == 8 && options_.block_height_px == 8) {
      return kernels_.sad8x8(block_, block_stride_, b, stride_);
    }
    return kernels_.sad(block_, block_stride_, b, stride_, width_bytes_, options_.block_height_px);
  }

  // SAD, or a partial sum > bound once it exceeds it.
  uint32_t boundedSadAt(int dx, int dy, uint32_t bound) const {
    const uint8_t* b = candidate(dx, dy);
    uint32_t sum = 0;
    for (int r = 0; r < options_.block_height_px && sum <= bound; r += kEarlyTerminationRows) {
      const int rows = std::min(kEarlyTerminationRows, options_.block_height_px - r);
      sum += kernels_.sad(block_ + r * block_stride_, block_stride_, b + r * stride_, stride_,
                          width_bytes_, rows);
    }
    return sum;
  }

  // Returns true when (dx, dy) became the best.
  bool consider(uint32_t sad, int dx, int dy) {
    const uint64_t rank = candidateRank(sad, dx, dy);
    if (rank >= best_rank_) {
      return false;
    }
    best_rank_ = rank;
    best_.dx = dx;
    best_.dy = dy;
    best_.sad = sad;
    return true;
  }

  bool tryCandidate(int dx, int dy) { return inWindow(dx, dy) && consider(sadAt(dx, dy), dx, dy); }

  void fullSearch() {
    for (int dy = dy_min_; dy <= dy_max_; ++dy) {
      for (int dx = dx_min_; dx <= dx_max_; ++dx) {
        consider(sadAt(dx, dy), dx, dy);
      }
    }
  }

  // Rings of growing Chebyshev radius around the zero vector.
  void spiralSearch() {
    const int radius = std::max({-dx_min_, dx_max_, -dy_min_, dy_max_});
    tryCandidate(0, 0);
    for (int ring = 1; ring <= radius; ++ring) {
      for (int dy = -ring; dy <= ring; ++dy) {
        const int step = (dy == -ring || dy == ring) ? 1 : 2 * ring;
        for (int dx = -ring; dx <= ring; dx += step) {
          if (inWindow(dx, dy)) {
            const uint32_t bound = static_cast<uint32_t>(best_rank_ >> 32);
            consider(boundedSadAt(dx, dy, bound), dx, dy);
          }
        }
      }
    }
  }

  void threeStepSearch() {
    int step = 1;
    while (2 * step <= options_.search_radius_px) {
      step *= 2;
    }
    tryCandidate(0, 0);
    for (; step >= 1; step /= 2) {
      const int cx = best_.dx;
      const int cy = best_.dy;
      for (int dy = -step; dy <= step; dy += step) {
        for (int dx = -step; dx <= step; dx += step) {
          tryCandidate(cx + dx, cy + dy);
        }
      }
    }
  }

  void diamondSearch() {
    static constexpr std::array<std::array<int, 2>, 8> kLarge{
        {{0, -2}, {1, -1}, {2, 0}, {1, 1}, {0, 2}, {-1, 1}, {-2, 0}, {-1, -1}}};
    static constexpr std::array<std::array<int, 2>, 4> kSmall{{{0, -1}, {1, 0}, {0, 1}, {-1, 0}}};
    tryCandidate(0, 0);
    const int max_steps = 2 * options_.search_radius_px + 1;
    for (int steps = 0; steps < max_steps; ++steps) {
      const int cx = best_.dx;
      const int cy = best_.dy;
      bool moved = false;
      for (const auto& [dx, dy] : kLarge) {
        moved |= tryCandidate(cx + dx, cy + dy);
      }
      if (!moved) {
        break;
      }
    }
    const int cx = best_.dx;
    const int cy = best_.dy;
    for (const auto& [dx, dy] : kSmall) {
      tryCandidate(cx + dx, cy + dy);
    }
  }

  // Sub-pixel offset along one axis; false when the minimum is on the window
  // edge (at_edge) or the SAD does not rise on both sides.
  bool refineAxis(int ux, int uy, float& offset, bool& at_edge) const {
    const int dx = best_.dx;
    const int dy = best_.dy;
    if (!inWindow(dx - ux, dy - uy) || !inWindow(dx + ux, dy + uy)) {
      at_edge = true;
      return false;
    }
    const std::optional<float> vertex =
        parabolaOffset(sadAt(dx - ux, dy - uy), best_.sad, sadAt(dx + ux, dy + uy));
    offset = vertex.value_or(0.0f);
    return vertex.has_value();
  }

  void refine() {
    float offset_x = 0.0f;
    float offset_y = 0.0f;
    bool at_edge = false;
    const bool refined_x = refineAxis(1, 0, offset_x, at_edge);
    const bool refined_y = refineAxis(0, 1, offset_y, at_edge);
    best_.subpixel_dx = static_cast<float>(best_.dx) + (refined_x ? offset_x : 0.0f);
    best_.subpixel_dy = static_cast<float>(best_.dy) + (refined_y ? offset_y : 0.0f);
    if (at_edge) {
      best_.status = MatchStatus::kAtSearchBoundary;
    } else if (!refined_x || !refined_y) {
      best_.status = MatchStatus::kTextureless;
    }
  }

  const BlockMatchingOptions& options_;
  const SadKernels& kernels_;
  const int channels_;
  const int width_bytes_;
  const uint8_t* block_;
  const ptrdiff_t block_stride_;
  const uint8_t* origin_;
  const ptrdiff_t stride_;
  const int dx_min_, dx_max_, dy_min_, dy_max_;
  BlockMatch best_;
  uint64_t best_rank_ = ~0ull;
};

BlockMatcher::BlockMatcher(const BlockMatchingOptions& options, SimdPath path)
    : options_(options), kernels_(&sadKernels(path)) {
  if (options.block_width_px < 1 || options.block_height_px < 1) {
    throw std::invalid_argument(fmt::format("block matching: block size {}x{} must be positive",
                                            options.block_width_px, options.block_height_px));
  }
  if (options.search_radius_px < 0 || options.search_radius_px > kMaxSearchRadiusPx) {
    throw std::invalid_argument(fmt::format("block matching: search radius {} px outside [0, {}]",
                                            options.search_radius_px, kMaxSearchRadiusPx));
  }
}

void BlockMatcher::validateFrames(const cv::Mat& reference, const cv::Mat& current) const {
  if (reference.empty() || current.empty()) {
    throw std::invalid_argument(fmt::format("block matching: the {} frame is empty",
                                            reference.empty() ? "reference" : "current"));
  }
  if (reference.type() != current.type() ||
      (reference.type() != CV_8UC1 && reference.type() != CV_8UC3)) {
    throw std::invalid_argument(
        "block matching: frames must both be 8-bit, 1 or 3 channels, of the same type");
  }
  const uint64_t max_sad = 255ull * static_cast<uint64_t>(options_.block_width_px) *
                           static_cast<uint64_t>(options_.block_height_px) * reference.channels();
  if (max_sad > UINT32_MAX) {
    throw std::invalid_argument(fmt::format("block matching: block {}x{} too large for 32-bit SADs",
                                            options_.block_width_px, options_.block_height_px));
  }
  if (reference.size() != current.size()) {
    throw std::invalid_argument(
        fmt::format("block matching: frame sizes differ: reference {}x{}, current {}x{}",
                    reference.cols, reference.rows, current.cols, current.rows));
  }
  if (options_.block_width_px > reference.cols || options_.block_height_px > reference.rows) {
    throw std::invalid_argument(fmt::format(
        "block matching: block {}x{} larger than the {}x{} frame", options_.block_width_px,
        options_.block_height_px, reference.cols, reference.rows));
  }
}

BlockMatch BlockMatcher::matchBlock(const cv::Mat& reference, const cv::Mat& current, int x,
                                    int y) const {
  validateFrames(reference, current);
  if (x < 0 || y < 0 || x + options_.block_width_px > reference.cols ||
      y + options_.block_height_px > reference.rows) {
    throw std::invalid_argument(fmt::format(
        "block matching: block at ({}, {}) of size {}x{} leaves the {}x{} frame", x, y,
        options_.block_width_px, options_.block_height_px, reference.cols, reference.rows));
  }
  return Search(*this, reference, current, x, y).run();
}

bool BlockMatcher::usesGridSearch(const cv::Mat& frame) const {
  const bool exhaustive = options_.strategy == SearchStrategy::kFull ||
                          options_.strategy == SearchStrategy::kFullEarlyTermination;
  return exhaustive && frame.channels() == 1 &&
         gridSearchSupports(options_.block_width_px, options_.block_height_px);
}

std::vector<BlockMatch> BlockMatcher::matchGrid(const cv::Mat& reference,
                                                const cv::Mat& current) const {
  validateFrames(reference, current);
  const int w = options_.block_width_px, h = options_.block_height_px;
  std::vector<BlockMatch> matches;
  if (!usesGridSearch(reference)) {
    for (int y = 0; y + h <= reference.rows; y += h) {
      for (int x = 0; x + w <= reference.cols; x += w) {
        matches.push_back(Search(*this, reference, current, x, y).run());
      }
    }
    return matches;
  }
  const int margin = gridSearchMarginBytes(options_.search_radius_px);
  const cv::Mat reference_margins = withMargins(reference, margin);
  const cv::Mat current_margins = withMargins(current, margin);
  const int columns = reference.cols / w;
  std::vector<BlockBest> winners(static_cast<size_t>(columns) * (reference.rows / h));
  kernels_->gridFullSearch({reference_margins.ptr<uint8_t>(), current_margins.ptr<uint8_t>(),
                            static_cast<ptrdiff_t>(reference_margins.step), reference.cols,
                            reference.rows, w, h, options_.search_radius_px},
                           winners.data());
  for (size_t i = 0; i < winners.size(); ++i) {
    const int x = static_cast<int>(i % columns) * w, y = static_cast<int>(i / columns) * h;
    matches.push_back(Search(*this, reference, current, x, y).refine(winners[i]));
  }
  return matches;
}

}  // namespace lineloc
