#include "robot/vision/edges/gaussian_smoother.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace lineloc {
namespace {

constexpr int kWeightBits = 10;
constexpr int kWeightSum = 1 << kWeightBits;
constexpr uint32_t kRounding = 1u << (2 * kWeightBits - 1);

}  // namespace

GaussianSmoother::GaussianSmoother(double sigma_px) {
  if (!(sigma_px > 0.0)) {
    throw std::invalid_argument("Gaussian smoothing: sigma_px must be positive");
  }
  radius_ = static_cast<int>(std::ceil(2.0 * sigma_px));
  std::vector<double> gaussian(2 * radius_ + 1);
  for (int k = -radius_; k <= radius_; ++k) {
    gaussian[k + radius_] = std::exp(-0.5 * k * k / (sigma_px * sigma_px));
  }
  const double total = std::accumulate(gaussian.begin(), gaussian.end(), 0.0);
  weights_.resize(gaussian.size());
  for (size_t i = 0; i < gaussian.size(); ++i) {
    weights_[i] = static_cast<uint16_t>(std::lround(kWeightSum * gaussian[i] / total));
  }
  const int sum = std::accumulate(weights_.begin(), weights_.end(), 0);
  weights_[radius_] = static_cast<uint16_t>(weights_[radius_] + kWeightSum - sum);
}

void GaussianSmoother::smooth(const cv::Mat& grey, cv::Mat& smoothed) {
  smoothed.create(grey.size(), CV_8UC1);
  const int width = grey.cols;
  const int height = grey.rows;
  column_sums_.resize(static_cast<size_t>(width) + 2 * radius_);
  row_totals_.resize(width);
  uint32_t* sums = column_sums_.data() + radius_;
  for (int y = 0; y < height; ++y) {
    std::fill(column_sums_.begin(), column_sums_.end(), 0);
    for (int k = -radius_; k <= radius_; ++k) {
      const uint8_t* row = grey.ptr<uint8_t>(std::clamp(y + k, 0, height - 1));
      const uint16_t weight = weights_[k + radius_];
      for (int x = 0; x < width; ++x) {
        sums[x] = sums[x] + weight * row[x];
      }
    }
    for (int x = 1; x <= radius_; ++x) {
      sums[-x] = sums[0];
      sums[width - 1 + x] = sums[width - 1];
    }
    uint32_t* totals = row_totals_.data();
    std::fill(row_totals_.begin(), row_totals_.end(), kRounding);
    for (int k = -radius_; k <= radius_; ++k) {
      const uint32_t weight = weights_[k + radius_];
      const uint32_t* shifted = sums + k;
      for (int x = 0; x < width; ++x) {
        totals[x] += weight * shifted[x];
      }
    }
    uint8_t* out = smoothed.ptr<uint8_t>(y);
    for (int x = 0; x < width; ++x) {
      out[x] = static_cast<uint8_t>(totals[x] >> (2 * kWeightBits));
    }
  }
}

}  // namespace lineloc
