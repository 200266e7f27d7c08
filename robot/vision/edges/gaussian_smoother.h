// Separable Gaussian smoothing of 8-bit images with fixed-point weights,
// written for the front end's steady state: the kernel is computed once and
// the row buffer reused, so a frame allocates nothing (OpenCV's GaussianBlur
// builds its kernel and filter engine on every call).
//
// w_k = round(2^8 exp(-k^2 / (2 sigma^2)) / Z), |k| <= ceil(2 sigma), adjusted
// so that sum w_k = 2^8; columns first into 16-bit sums t (<= 255 x 2^8),
// then rows in 32 bits, rounded to 4 fractional bits:
//   out = (sum_k w_k t(x + k) + 2^11) >> 12  (16 x grey level, <= 4080);
// rounding to whole grey levels would add noise of 0.3 grey levels, as much
// as the sensor noise left after smoothing, and bias sub-pixel edges.
// Borders replicate. Both passes are SIMD (Highway, dispatched at run time to
// the best instruction set the processor has, down to plain scalar code).
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace lineloc {

class GaussianSmoother {
 public:
  static constexpr int kOutputGain = 16;

  // sigma_px > 0.
  explicit GaussianSmoother(double sigma_px);

  // `grey`: CV_8UC1. `smoothed` is (re)created with the same size, CV_16UC1,
  // kOutputGain x grey levels.
  void smooth(const cv::Mat& grey, cv::Mat& smoothed);

 private:
  int radius_;
  std::vector<uint16_t> weights_;      // 2 radius + 1 taps, sum 2^8
  std::vector<const uint8_t*> rows_;   // the 2 radius + 1 input rows of an output row
  std::vector<uint16_t> column_sums_;  // width + 2 radius, borders replicated
};

}  // namespace lineloc
