#include "robot/vision/flow/correlation_flow.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "robot/vision/block_matching/block_matcher.h"
#include "robot/vision/block_matching/parabola_fit.h"

namespace lineloc {
namespace {

// 1-D search of one block along `direction` (unit length).
class LineSearch {
 public:
  LineSearch(const SadKernels& kernels, const cv::Mat& previous, const cv::Mat& current,
             const cv::Rect& block, cv::Point2f direction, int radius_px)
      : kernels_(kernels),
        previous_(previous),
        current_(current),
        block_(block),
        direction_(direction),
        radius_px_(radius_px) {}

  // Flow of the block, or nullopt when the minimum is not one across the
  // line too, or flat.
  std::optional<cv::Point2f> run() const {
    const int count = 2 * radius_px_ + 1;
    std::vector<uint32_t> sads(count, UINT32_MAX);
    int best = -1;
    for (int k = 0; k < count; ++k) {
      const int t = k - radius_px_;
      if (const auto sad = sadAt(t)) {
        sads[k] = *sad;
        const bool better = best < 0 || *sad < sads[best] ||
                            (*sad == sads[best] && std::abs(t) < std::abs(best - radius_px_));
        best = better ? k : best;
      }
    }
    if (best < 0) {
      return std::nullopt;
    }
    const cv::Point at = displacement(best - radius_px_);
    const auto offset_x = axisOffset(at, {1, 0}, sads[best]);
    const auto offset_y = axisOffset(at, {0, 1}, sads[best]);
    if (!offset_x || !offset_y) {
      return std::nullopt;
    }
    return cv::Point2f(static_cast<float>(at.x) + *offset_x, static_cast<float>(at.y) + *offset_y);
  }

 private:
  cv::Point displacement(int t) const {
    return {static_cast<int>(std::lround(t * direction_.x)),
            static_cast<int>(std::lround(t * direction_.y))};
  }

  // Parabola offset along `axis` around the integer displacement `at`.
  std::optional<float> axisOffset(cv::Point at, cv::Point axis, uint32_t centre) const {
    const auto minus = sadAt(at - axis);
    const auto plus = sadAt(at + axis);
    if (!minus || !plus || *minus < centre || *plus < centre) {
      return std::nullopt;
    }
    return parabolaOffset(*minus, centre, *plus);
  }

  std::optional<uint32_t> sadAt(int t) const { return sadAt(displacement(t)); }

  std::optional<uint32_t> sadAt(cv::Point offset) const {
    const int x = block_.x + offset.x;
    const int y = block_.y + offset.y;
    if (x < 0 || y < 0 || x + block_.width > current_.cols || y + block_.height > current_.rows) {
      return std::nullopt;
    }
    const int channels = previous_.channels();
    return kernels_.sad(previous_.ptr<uint8_t>(block_.y) + block_.x * channels, previous_.step,
                        current_.ptr<uint8_t>(y) + x * channels, current_.step,
                        block_.width * channels, block_.height);
  }

  const SadKernels& kernels_;
  const cv::Mat& previous_;
  const cv::Mat& current_;
  cv::Rect block_;
  cv::Point2f direction_;
  int radius_px_;
};

cv::Point2f unitDirection(const cv::Point2f& direction) {
  const double length = std::hypot(direction.x, direction.y);
  if (!(length > 1e-6) || !std::isfinite(length)) {
    throw std::invalid_argument(fmt::format(
        "optical flow: expected direction ({}, {}) has no length", direction.x, direction.y));
  }
  return direction * static_cast<float>(1.0 / length);
}

}  // namespace

FlowField computeCorrelationFlow(const cv::Mat& previous, const cv::Mat& current,
                                 const FlowOptions& options, SimdPath path) {
  FlowField field;
  field.motion = detectMotion(previous, current, options.motion);
  const int size = options.block_size_px;
  if (size < 1 || size > previous.cols || size > previous.rows) {
    throw std::invalid_argument(
        fmt::format("optical flow: block {} px does not fit the {}x{} frame", size, previous.cols,
                    previous.rows));
  }
  const BlockMatcher matcher({size, size, options.search_radius_px, SearchStrategy::kFull}, path);
  std::optional<cv::Point2f> direction;
  if (options.expected_direction) {
    direction = unitDirection(*options.expected_direction);
  }
  field.flow_px = cv::Mat(previous.size(), CV_32FC2, cv::Scalar(0, 0));
  field.known = cv::Mat(previous.size(), CV_8U, cv::Scalar(0));
  const double min_moving = options.min_moving_fraction * size * size;
  for (int y = 0; y + size <= previous.rows; y += size) {
    for (int x = 0; x + size <= previous.cols; x += size) {
      FlowBlock block{cv::Rect(x, y, size, size), {0.0f, 0.0f}, false, true};
      block.moving = cv::countNonZero(field.motion.moving(block.block)) >= min_moving;
      if (block.moving && direction) {
        const auto flow = LineSearch(sadKernels(path), previous, current, block.block, *direction,
                                     options.search_radius_px)
                              .run();
        block.known = flow.has_value();
        block.flow_px = flow.value_or(cv::Point2f());
      } else if (block.moving) {
        const BlockMatch match = matcher.matchBlock(previous, current, x, y);
        block.known = match.status == MatchStatus::kMatched;
        block.flow_px = {match.subpixel_dx, match.subpixel_dy};
      }
      if (block.known) {
        field.flow_px(block.block).setTo(cv::Scalar(block.flow_px.x, block.flow_px.y));
        field.known(block.block).setTo(255);
      }
      field.blocks.push_back(block);
    }
  }
  return field;
}

}  // namespace lineloc
