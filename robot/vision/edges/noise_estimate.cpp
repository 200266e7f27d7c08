#include "robot/vision/edges/noise_estimate.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace lineloc {
namespace {

constexpr int kMaxResponse = 16 * 255;
// 6 = sqrt(sum N^2); 0.6745 = Phi^-1(3/4), the median of |Z| for Z ~ N(0, 1).
constexpr double kMedianToSigma = 1.0 / (6.0 * 0.674489750196082);

}  // namespace

NoiseEstimator::NoiseEstimator(int row_step) : row_step_(row_step), histogram_(kMaxResponse + 1) {
  if (row_step < 1) {
    throw std::invalid_argument("noise estimator: row_step must be >= 1");
  }
}

double NoiseEstimator::estimate(const cv::Mat& grey) {
  CV_Assert(grey.type() == CV_8UC1 && grey.rows >= 3 && grey.cols >= 3);
  std::fill(histogram_.begin(), histogram_.end(), 0u);
  uint32_t count = 0;
  for (int y = 1; y + 1 < grey.rows; y += row_step_) {
    const uint8_t* above = grey.ptr<uint8_t>(y - 1);
    const uint8_t* row = grey.ptr<uint8_t>(y);
    const uint8_t* below = grey.ptr<uint8_t>(y + 1);
    // r = c(x - 1) - 2 c(x) + c(x + 1), c = above - 2 row + below.
    int c_left = above[0] - 2 * row[0] + below[0];
    int c_mid = above[1] - 2 * row[1] + below[1];
    for (int x = 1; x + 1 < grey.cols; ++x) {
      const int c_right = above[x + 1] - 2 * row[x + 1] + below[x + 1];
      ++histogram_[std::abs(c_left - 2 * c_mid + c_right)];
      c_left = c_mid;
      c_mid = c_right;
    }
    count += static_cast<uint32_t>(grey.cols - 2);
  }
  const double half = 0.5 * count;
  double below = 0.0;
  for (int v = 0; v <= kMaxResponse; ++v) {
    const double in_bin = histogram_[v];
    if (below + in_bin >= half) {
      const double bin_start = v == 0 ? 0.0 : v - 0.5;
      const double bin_width = v == 0 ? 0.5 : 1.0;
      return kMedianToSigma * (bin_start + bin_width * (half - below) / in_bin);
    }
    below += in_bin;
  }
  return kMedianToSigma * kMaxResponse;
}

}  // namespace lineloc
