// Separable Gaussian smoothing of 8-bit images with fixed-point weights,
// written for the front end's steady state: the kernel is computed once and
// the row buffer reused, so a frame allocates nothing (OpenCV's GaussianBlur
// builds its kernel and filter engine on every call), and one row at a time,
// so that the rows are still in cache when the gradient needs them.
//
// w_k = round(2^8 exp(-k^2 / (2 sigma^2)) / Z), |k| <= ceil(2 sigma), adjusted
// so that sum w_k = 2^8 (sigma >= 1/2 keeps every w_k < 2^8); columns first
// into 16-bit sums t = sum_k w_k I(y + k) <= 255 x 2^8, then rows:
//   out = (sum_k floor(t(x + k) w_k / 2^8) + 2^3) >> 4  (16 x grey level, <= 4080),
// all in 16 bits; the floors lose < 2^-4 of an output unit on average.
// Rounding to whole grey levels would add noise of 0.3 grey levels, as much
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
  static constexpr double kMinSigmaPx = 0.5;

  // sigma_px >= kMinSigmaPx.
  explicit GaussianSmoother(double sigma_px);

  // Row y of the smoothed `grey` (CV_8UC1), kOutputGain x grey levels, into
  // `out` (grey.cols values).
  void smoothRow(const cv::Mat& grey, int y, uint16_t* out);

  // The weights w_k / 2^8, k = -radius .. radius, summing to 1.
  std::vector<double> kernel() const;

 private:
  int radius_;
  std::vector<uint16_t> weights_;      // 2 radius + 1 taps, sum 2^8
  std::vector<const uint8_t*> rows_;   // the 2 radius + 1 input rows of an output row
  std::vector<uint16_t> column_sums_;  // width + 2 radius, borders replicated
};

}  // namespace lineloc
