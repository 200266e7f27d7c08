#include "robot/vision/stereo/sad_stereo_matcher.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

namespace lineloc {
namespace {

// The disparity search of one image pair with Cost-bit costs: the column
// sums and block costs of every disparity, one image row at a time
// (disparity_kernels.h), and the winner of each pixel.
template <typename Cost>
class DisparitySearch {
 public:
  DisparitySearch(const StereoOptions& options, const DisparityKernels<Cost>& kernels,
                  const cv::Mat& left, const cv::Mat& right)
      : options_(options),
        kernels_(kernels),
        left_(left),
        right_(right),
        width_(left.cols),
        half_(options.block_size_px / 2),
        count_(options.num_disparities),
        columns_(static_cast<size_t>(count_) * width_, 0),
        costs_(static_cast<size_t>(count_) * width_, kNoCost<Cost>),
        scratch_(2 * static_cast<size_t>(width_)),
        no_costs_(width_, kNoCost<Cost>),
        best_(width_),
        index_(width_),
        minus_(width_),
        plus_(width_),
        limit_(width_),
        ambiguous_(width_),
        right_best_(width_),
        right_index_(width_) {}

  DisparityMap run() {
    DisparityMap map{cv::Mat(left_.size(), CV_32F, cv::Scalar(0)),
                     cv::Mat(left_.size(), CV_8U, cv::Scalar(0))};
    const int block = options_.block_size_px;
    for (int row = 0; row < block; ++row) {
      forEachDisparity([&](int, int d, int count) {
        kernels_.addRow(left_.ptr<uint8_t>(row) + d, right_.ptr<uint8_t>(row), count, columns(d));
      });
    }
    for (int y = half_; y + half_ < left_.rows; ++y) {
      if (y > half_) {
        slideColumns(y + half_, y - half_ - 1);
      }
      blockCosts();
      chooseRow(map.disparity_px.ptr<float>(y), map.valid.ptr<uint8_t>(y));
    }
    return map;
  }

 private:
  // f(k, d, count) for the disparities d = min + k whose columns x in
  // [d, width) are not empty.
  template <typename F>
  void forEachDisparity(F&& f) const {
    for (int k = 0; k < count_; ++k) {
      const int d = options_.min_disparity_px + k;
      if (d < width_) {
        f(k, d, width_ - d);
      }
    }
  }

  Cost* columns(int d) {
    return columns_.data() + static_cast<size_t>(d - options_.min_disparity_px) * width_ + d;
  }
  Cost* costs(int k) { return costs_.data() + static_cast<size_t>(k) * width_; }

  void slideColumns(int row_in, int row_out) {
    forEachDisparity([&](int, int d, int count) {
      kernels_.slideRow(left_.ptr<uint8_t>(row_in) + d, right_.ptr<uint8_t>(row_in),
                        left_.ptr<uint8_t>(row_out) + d, right_.ptr<uint8_t>(row_out), count,
                        columns(d));
    });
  }

  // costs(k)[x] for x in [d + h, width - h): the block sums; kNoCost
  // elsewhere since construction.
  void blockCosts() {
    const int block = options_.block_size_px;
    forEachDisparity([&](int k, int d, int count) {
      if (count >= block) {
        kernels_.windowSums(columns(d), count, block, costs(k) + d + half_, scratch_.data());
      }
    });
  }

  void chooseRow(float* disparity, uint8_t* valid) {
    std::fill(best_.begin(), best_.end(), kNoCost<Cost>);
    std::fill(index_.begin(), index_.end(), Cost{0});
    for (int k = 0; k < count_; ++k) {
      kernels_.considerDisparity(costs(k), k > 0 ? costs(k - 1) : no_costs_.data(),
                                 static_cast<Cost>(k), width_, best_.data(), index_.data(),
                                 minus_.data(), plus_.data());
    }
    std::fill(ambiguous_.begin(), ambiguous_.end(), uint8_t{0});
    if (options_.uniqueness_percent > 0) {
      markAmbiguous();
    }
    kernels_.subpixelWinners(best_.data(), index_.data(), minus_.data(), plus_.data(),
                             ambiguous_.data(), options_.min_disparity_px, count_ - 1, width_,
                             disparity, valid);
    if (options_.max_left_right_difference_px >= 0) {
      rightWinners();
      for (int x = 0; x < width_; ++x) {
        if (valid[x] && !consistentWithRight(x, disparity[x])) {
          disparity[x] = 0.0f;
          valid[x] = 0;
        }
      }
    }
  }

  // A cost within uniqueness_percent of the best, further than one from it:
  // cost * 100 <= best * (100 + u), i.e. cost <= floor(best (100 + u) / 100).
  void markAmbiguous() {
    kernels_.uniquenessLimits(best_.data(), 100 + options_.uniqueness_percent, width_,
                              limit_.data());
    for (int k = 0; k < count_; ++k) {
      kernels_.markAmbiguous(costs(k), limit_.data(), index_.data(), static_cast<Cost>(k), width_,
                             ambiguous_.data());
    }
  }

  // Winner over d of the right image's pixel xr: argmin_k costs(k)[xr + d_k].
  void rightWinners() {
    std::fill(right_best_.begin(), right_best_.end(), kNoCost<Cost>);
    forEachDisparity([&](int k, int d, int count) {
      kernels_.considerRight(costs(k) + d, static_cast<Cost>(k), count, right_best_.data(),
                             right_index_.data());
    });
  }

  bool consistentWithRight(int x, float disparity_px) const {
    const int xr = x - static_cast<int>(std::lround(disparity_px));
    if (xr < 0 || right_best_[xr] == kNoCost<Cost>) {
      return false;
    }
    return std::abs(options_.min_disparity_px + static_cast<int>(right_index_[xr]) - (x - xr)) <=
           options_.max_left_right_difference_px;
  }

  const StereoOptions& options_;
  const DisparityKernels<Cost>& kernels_;
  const cv::Mat& left_;
  const cv::Mat& right_;
  const int width_, half_, count_;
  std::vector<Cost> columns_;  // per disparity k: column sums at x in [d_k, width)
  std::vector<Cost> costs_;    // per disparity k: block costs
  std::vector<Cost> scratch_;
  const std::vector<Cost> no_costs_;
  std::vector<Cost> best_, index_, minus_, plus_, limit_;
  std::vector<uint8_t> ambiguous_;
  std::vector<Cost> right_best_, right_index_;
};

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
  if (options.block_size_px < 3 || options.block_size_px > kMaxStereoBlockPx ||
      options.block_size_px % 2 == 0) {
    throw std::invalid_argument(fmt::format("stereo: block size {} px must be odd, in [3, {}]",
                                            options.block_size_px, kMaxStereoBlockPx));
  }
  if (options.min_disparity_px < 0 || options.num_disparities < 1) {
    throw std::invalid_argument(
        fmt::format("stereo: disparity range [{}, +{}) needs min >= 0 and at least one disparity",
                    options.min_disparity_px, options.num_disparities));
  }
  if (options.uniqueness_percent < 0 || options.uniqueness_percent > kMaxUniquenessPercent) {
    throw std::invalid_argument(fmt::format("stereo: uniqueness_percent {} outside [0, {}]",
                                            options.uniqueness_percent, kMaxUniquenessPercent));
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
  const uint64_t largest_pixel_cost =
      options_.prefilter_cap > 0 ? 2 * static_cast<uint64_t>(options_.prefilter_cap) : 255;
  const bool fits_16_bits =
      static_cast<uint64_t>(block) * block * largest_pixel_cost < kNoCost<uint16_t> &&
      options_.num_disparities < kNoCost<uint16_t>;
  if (fits_16_bits) {
    return DisparitySearch<uint16_t>(options_, kernels_->disparity16, left, right).run();
  }
  return DisparitySearch<uint32_t>(options_, kernels_->disparity32, left, right).run();
}

}  // namespace lineloc
