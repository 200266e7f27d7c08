#include "robot/vision/stereo/sad_stereo_matcher.h"

#include <fmt/format.h>

#include <limits>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

#include "robot/vision/block_matching/parabola_fit.h"

namespace lineloc {
namespace {

constexpr uint32_t kNoCost = std::numeric_limits<uint32_t>::max();

// Block sums of |L(x) - R(x - d)| for one disparity: column sums over the
// block's rows, kept up to date as the block slides down one row.
class DisparityColumnSums {
 public:
  DisparityColumnSums(int disparity, int width) : disparity_(disparity), columns_(width, 0) {}

  // Adds (sign +1) or removes (sign -1) image row `row` of both images.
  void update(const SadKernels& kernels, const uint8_t* left, const uint8_t* right, int width,
              int sign, std::vector<uint8_t>& scratch) {
    const int count = width - disparity_;
    if (count <= 0) {
      return;
    }
    kernels.absDiffRow(left + disparity_, right, count, scratch.data());
    uint32_t* column = columns_.data() + disparity_;
    for (int x = 0; x < count; ++x) {
      column[x] += static_cast<uint32_t>(sign * scratch[x]);
    }
  }

  // costs[x] = sum of the columns x - h .. x + h, for blocks that lie in both
  // images (x - h >= disparity, x + h < width); kNoCost elsewhere.
  void blockSums(int half, uint32_t* costs) const {
    const int width = static_cast<int>(columns_.size());
    std::fill(costs, costs + width, kNoCost);
    const int first = disparity_ + half;
    if (first + half >= width) {
      return;
    }
    uint32_t sum = 0;
    for (int x = disparity_; x < first + half; ++x) {
      sum += columns_[x];
    }
    for (int x = first; x + half < width; ++x) {
      sum += columns_[x + half];
      costs[x] = sum;
      sum -= columns_[x - half];
    }
  }

 private:
  int disparity_;
  std::vector<uint32_t> columns_;
};

struct PixelChoice {
  bool valid;
  float disparity_px;
};

// Winner takes all over costs[k * stride] for the disparities k, with the
// uniqueness test and the parabola refinement.
PixelChoice choose(const uint32_t* costs, ptrdiff_t stride, int count, int min_disparity,
                   int uniqueness_percent) {
  int best = -1;
  uint32_t best_cost = kNoCost;
  for (int k = 0; k < count; ++k) {
    if (costs[k * stride] < best_cost) {
      best_cost = costs[k * stride];
      best = k;
    }
  }
  if (best < 0 || best == 0 || best == count - 1 || costs[(best - 1) * stride] == kNoCost) {
    return {false, 0.0f};
  }
  const uint64_t limit = static_cast<uint64_t>(best_cost) * (100 + uniqueness_percent);
  for (int k = 0; k < count; ++k) {
    if (std::abs(k - best) > 1 && costs[k * stride] != kNoCost &&
        static_cast<uint64_t>(costs[k * stride]) * 100 <= limit && uniqueness_percent > 0) {
      return {false, 0.0f};
    }
  }
  const std::optional<float> offset =
      equiangularOffset(costs[(best - 1) * stride], best_cost, costs[(best + 1) * stride]);
  if (!offset) {
    return {false, 0.0f};
  }
  return {true, static_cast<float>(min_disparity + best) + *offset};
}

// Integer disparity index of least cost seen from each right-image pixel xr:
// argmin_k costs[k][xr + d_k], -1 where no block fits.
void rightWinners(const uint32_t* costs, int count, int width, int min_disparity,
                  std::vector<int>& winners) {
  std::vector<uint32_t> best(width, kNoCost);
  winners.assign(width, -1);
  for (int k = 0; k < count; ++k) {
    const uint32_t* row = costs + static_cast<size_t>(k) * width;
    const int d = min_disparity + k;
    for (int xr = 0; xr + d < width; ++xr) {
      if (row[xr + d] < best[xr]) {
        best[xr] = row[xr + d];
        winners[xr] = k;
      }
    }
  }
}

// cap + clamp(Sobel_x(image), -cap, cap), in [0, 2 cap].
cv::Mat clippedXSobel(const cv::Mat& image, int cap) {
  cv::Mat derivative, clipped;
  cv::Sobel(image, derivative, CV_16S, 1, 0, 3);
  cv::Mat limited = cv::max(cv::min(derivative, cap), -cap);
  limited.convertTo(clipped, CV_8U, 1.0, cap);
  return clipped;
}

}  // namespace

SadStereoMatcher::SadStereoMatcher(const StereoOptions& options, SimdPath path)
    : options_(options), kernels_(&sadKernels(path)) {
  if (options.block_size_px < 3 || options.block_size_px % 2 == 0) {
    throw std::invalid_argument(
        fmt::format("stereo: block size {} px must be odd and >= 3", options.block_size_px));
  }
  if (options.min_disparity_px < 0 || options.num_disparities < 1) {
    throw std::invalid_argument(
        fmt::format("stereo: disparity range [{}, +{}) needs min >= 0 and at least one disparity",
                    options.min_disparity_px, options.num_disparities));
  }
  if (options.uniqueness_percent < 0) {
    throw std::invalid_argument("stereo: uniqueness_percent must be >= 0");
  }
  if (options.prefilter_cap < 0 || options.prefilter_cap > 127) {
    throw std::invalid_argument(
        fmt::format("stereo: prefilter_cap {} outside [0, 127]", options.prefilter_cap));
  }
}

DisparityMap SadStereoMatcher::compute(const cv::Mat& left_image,
                                       const cv::Mat& right_image) const {
  validate(left_image, right_image);
  if (options_.prefilter_cap == 0) {
    return match(left_image, right_image);
  }
  return match(clippedXSobel(left_image, options_.prefilter_cap),
               clippedXSobel(right_image, options_.prefilter_cap));
}

void SadStereoMatcher::validate(const cv::Mat& left, const cv::Mat& right) const {
  if (left.empty() || right.empty()) {
    throw std::invalid_argument(
        fmt::format("stereo: the {} image is empty", left.empty() ? "left" : "right"));
  }
  if (left.type() != CV_8UC1 || right.type() != CV_8UC1) {
    throw std::invalid_argument("stereo: images must be 8-bit single channel");
  }
  if (left.size() != right.size()) {
    throw std::invalid_argument(fmt::format("stereo: image sizes differ: left {}x{}, right {}x{}",
                                            left.cols, left.rows, right.cols, right.rows));
  }
  const int block = options_.block_size_px;
  if (block > left.cols || block > left.rows) {
    throw std::invalid_argument(fmt::format("stereo: block {} px larger than the {}x{} images",
                                            block, left.cols, left.rows));
  }
}

DisparityMap SadStereoMatcher::match(const cv::Mat& left, const cv::Mat& right) const {
  const int block = options_.block_size_px;
  const int width = left.cols;
  const int half = block / 2;
  const int count = options_.num_disparities;
  std::vector<DisparityColumnSums> sums;
  for (int k = 0; k < count; ++k) {
    sums.emplace_back(options_.min_disparity_px + k, width);
  }
  std::vector<uint8_t> scratch(width);
  std::vector<uint32_t> costs(static_cast<size_t>(count) * width);
  const auto update = [&](int row, int sign) {
    for (DisparityColumnSums& sum : sums) {
      sum.update(*kernels_, left.ptr<uint8_t>(row), right.ptr<uint8_t>(row), width, sign, scratch);
    }
  };
  for (int row = 0; row < block - 1; ++row) {
    update(row, +1);
  }
  const bool check_left_right = options_.max_left_right_difference_px >= 0;
  std::vector<int> right_winners;
  DisparityMap map{cv::Mat(left.size(), CV_32F, cv::Scalar(0)),
                   cv::Mat(left.size(), CV_8U, cv::Scalar(0))};
  for (int y = half; y + half < left.rows; ++y) {
    update(y + half, +1);
    for (int k = 0; k < count; ++k) {
      sums[k].blockSums(half, costs.data() + static_cast<size_t>(k) * width);
    }
    if (check_left_right) {
      rightWinners(costs.data(), count, width, options_.min_disparity_px, right_winners);
    }
    float* disparity = map.disparity_px.ptr<float>(y);
    uint8_t* valid = map.valid.ptr<uint8_t>(y);
    for (int x = 0; x < width; ++x) {
      PixelChoice choice = choose(costs.data() + x, width, count, options_.min_disparity_px,
                                  options_.uniqueness_percent);
      if (choice.valid && check_left_right) {
        const int xr = x - static_cast<int>(std::lround(choice.disparity_px));
        const int k = xr >= 0 ? right_winners[xr] : -1;
        choice.valid = k >= 0 && std::abs(options_.min_disparity_px + k - (x - xr)) <=
                                     options_.max_left_right_difference_px;
      }
      disparity[x] = choice.valid ? choice.disparity_px : 0.0f;
      valid[x] = choice.valid ? 255 : 0;
    }
    update(y - half, -1);
  }
  return map;
}

}  // namespace lineloc
