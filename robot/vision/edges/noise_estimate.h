// The standard deviation of an image's white Gaussian noise, from the image
// alone: Immerkaer's high-pass (J. Immerkaer, "Fast noise variance
// estimation", CVIU 64(2), 1996, eq. 1)
//   N = [1 -2 1; -2 4 -2; 1 -2 1],
// the difference of two Laplacians, cancels every locally quadratic image, so
// r = N * I is noise wherever the image is smooth, with variance
// sum N^2 sigma^2 = 36 sigma^2. Immerkaer's eq. 3 takes sigma from the mean
// |r|, which edges and texture inflate; here the median absolute value, as
// Donoho & Johnstone's (Biometrika 81(3), 1994, sec. 4.2) wavelet estimate
// does:
//   sigma = median |r| / (6 Phi^-1(3/4)),  Phi^-1(3/4) = 0.6745,
// which holds while fewer than half the pixels are on structure. |r| is an
// integer; the median is interpolated within its histogram bin, bin v
// covering [v - 1/2, v + 1/2) (bin 0: [0, 1/2)). One row in row_step is used.
// No allocation once constructed.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace lineloc {

class NoiseEstimator {
 public:
  // Throws std::invalid_argument unless row_step >= 1.
  explicit NoiseEstimator(int row_step = 8);

  // Noise standard deviation of `grey` (CV_8UC1, at least 3 x 3), grey levels.
  double estimate(const cv::Mat& grey);

 private:
  int row_step_;
  std::vector<uint32_t> histogram_;  // of |r|, 0 .. 16 x 255
};

}  // namespace lineloc
