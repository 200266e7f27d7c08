// Dense disparity of a rectified stereo pair by SAD block matching, the
// stereo use of Persa & Jonker's §4 SAD (eq. 7): for each left pixel (x, y)
// and disparity d,
//
//   C(x, y, d) = sum_{|i|, |j| <= h} |L(x + i, y + j) - R(x + i - d, y + j)|,
//
// block (2h + 1)^2, winner takes all, sub-pixel by the equiangular (V) fit
// through C(d - 1), C(d), C(d + 1) (disparity_kernels.h: exact for a SAD). The
// cost volume is swept one image row at a time on the SAD kernels' SIMD path
// (block_matching/disparity_kernels.h): column sums slid down the image, block
// sums by power-of-two partial sums along x, and the winner searches, all as
// passes along x over one row of costs per disparity, so the cost per pixel
// and disparity grows only with log2 of the block.
//
// With prefilter_cap > 0 both images are first replaced by their clipped
// horizontal Sobel derivative (cv::StereoBM's XSOBEL pre-filter).
//
// A pixel is valid when its block lies in both images for at least one
// disparity of the range, the minimum is unique (no disparity further than
// one from the best within uniqueness_percent of its cost) and the cost rises
// on both sides of it, and (when enabled) the right image's best match for
// x - d points back to within max_left_right_difference_px of d.
#pragma once

#include <opencv2/core.hpp>

#include "robot/vision/block_matching/sad_kernels.h"

namespace lineloc {

inline constexpr int kMaxStereoBlockPx = 255;
inline constexpr int kMaxUniquenessPercent = 1000;

struct StereoOptions {
  int block_size_px = 15;      // odd, in [3, kMaxStereoBlockPx]
  int min_disparity_px = 0;    // >= 0
  int num_disparities = 64;    // >= 1
  int uniqueness_percent = 0;  // in [0, kMaxUniquenessPercent]
  // > 0: match min(max(dI/dx, -cap), cap) (Sobel 3x3) instead of grey levels,
  // as cv::StereoBM's default pre-filter does; robust to exposure changes.
  int prefilter_cap = 31;
  // >= 0: left-right check, the right image's own winner at x - d must lie
  // within this many pixels of d; < 0: no check.
  int max_left_right_difference_px = 1;
};

struct DisparityMap {
  cv::Mat disparity_px;  // CV_32F, left image geometry; 0 where not valid
  cv::Mat valid;         // CV_8U, 255 where disparity_px holds an estimate
};

class SadStereoMatcher {
 public:
  // Throws std::invalid_argument for options outside their ranges.
  explicit SadStereoMatcher(const StereoOptions& options, SimdPath path = bestSimdPath());

  // `left`, `right`: rectified CV_8UC1 of the same size, larger than a block;
  // throws std::invalid_argument naming the problem otherwise.
  DisparityMap compute(const cv::Mat& left, const cv::Mat& right) const;

 private:
  void validate(const cv::Mat& left, const cv::Mat& right) const;
  DisparityMap match(const cv::Mat& left, const cv::Mat& right) const;

  StereoOptions options_;
  const SadKernels* kernels_;
};

}  // namespace lineloc
