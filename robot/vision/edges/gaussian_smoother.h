// Separable Gaussian smoothing of 8-bit images with fixed-point weights,
// written for the front end's steady state: the kernel is computed once and
// the row buffer reused, so a frame allocates nothing (OpenCV's GaussianBlur
// builds its kernel and filter engine on every call).
//
// w_k = round(2^10 exp(-k^2 / (2 sigma^2)) / Z), |k| <= ceil(2 sigma), adjusted
// so that sum w_k = 2^10; columns first into 32-bit sums (<= 255 x 2^10), then
// rows, rounded: out = (sum_k w_k t(x + k) + 2^19) >> 20. Borders replicate.
// The loops over x have no dependencies, so the compiler vectorises them.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace lineloc {

class GaussianSmoother {
 public:
  // sigma_px > 0.
  explicit GaussianSmoother(double sigma_px);

  // `grey`: CV_8UC1. `smoothed` is (re)created with the same size.
  void smooth(const cv::Mat& grey, cv::Mat& smoothed);

 private:
  int radius_;
  std::vector<uint16_t> weights_;  // 2 radius + 1 taps, sum 2^10
  std::vector<uint32_t> column_sums_;
  std::vector<uint32_t> row_totals_;
};

}  // namespace lineloc
