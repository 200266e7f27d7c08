#include "robot/vision/edges/edge_detector.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace lineloc {
namespace {

// Sobel 3x3 on a ramp of slope s gives 8 s.
constexpr float kSobelGain = 8.0f;
// |gy| <= tan(22.5 deg) |gx| selects the horizontal neighbours; 2/5 ~ 0.414.
constexpr int kTanNumerator = 2;
constexpr int kTanDenominator = 5;
// Room for the step samples 3 px either side.
constexpr int kStepSampleDistancePx = 3;
constexpr int kBorderPx = kStepSampleDistancePx;

struct Direction {
  int dx, dy;
};

// Gradient direction quantised to one of 4 neighbour axes, pointing dark -> bright.
Direction quantise(int gx, int gy) {
  const int ax = std::abs(gx);
  const int ay = std::abs(gy);
  Direction d{1, 0};
  if (ay * kTanDenominator <= ax * kTanNumerator) {
    d = {1, 0};
  } else if (ax * kTanDenominator <= ay * kTanNumerator) {
    d = {0, 1};
  } else {
    d = {1, (gx > 0) == (gy > 0) ? 1 : -1};
  }
  if (d.dx * gx + d.dy * gy < 0) {
    d = {-d.dx, -d.dy};
  }
  return d;
}

}  // namespace

EdgeDetector::EdgeDetector(const EdgeDetectorOptions& options) : options_(options) {
  if (!(options.smoothing_sigma_px >= 0.0) || !(options.min_gradient > 0.0f)) {
    throw std::invalid_argument(
        "edge detector: smoothing_sigma_px must be >= 0 and min_gradient > 0");
  }
  if (options.smoothing_sigma_px > 0.0) {
    smoother_.emplace(options.smoothing_sigma_px);
  }
  const double min_sobel = options.min_gradient * kSobelGain;
  min_squared_sobel_ = static_cast<int64_t>(std::ceil(min_sobel * min_sobel));
}

void EdgeDetector::detect(const cv::Mat& grey) {
  if (smoother_) {
    smoother_->smooth(grey, smoothed_);
  } else {
    grey.copyTo(smoothed_);
  }
  cv::spatialGradient(smoothed_, gradient_x_, gradient_y_, 3);
  computeSquaredMagnitude();
  suppressNonMaxima();
}

void EdgeDetector::computeSquaredMagnitude() {
  squared_magnitude_.create(gradient_x_.size(), CV_32S);
  for (int y = 0; y < gradient_x_.rows; ++y) {
    const int16_t* gx = gradient_x_.ptr<int16_t>(y);
    const int16_t* gy = gradient_y_.ptr<int16_t>(y);
    int32_t* m = squared_magnitude_.ptr<int32_t>(y);
    for (int x = 0; x < gradient_x_.cols; ++x) {
      m[x] = gx[x] * gx[x] + gy[x] * gy[x];
    }
  }
}

void EdgeDetector::suppressNonMaxima() {
  point_index_.create(gradient_x_.size(), CV_32S);
  std::fill_n(point_index_.ptr<int32_t>(), point_index_.total(), -1);
  points_.clear();
  const int stride = static_cast<int>(squared_magnitude_.step1());
  const int smoothed_stride = static_cast<int>(smoothed_.step1());
  for (int y = kBorderPx; y < gradient_x_.rows - kBorderPx; ++y) {
    const int32_t* m = squared_magnitude_.ptr<int32_t>(y);
    const int16_t* gx = gradient_x_.ptr<int16_t>(y);
    const int16_t* gy = gradient_y_.ptr<int16_t>(y);
    const uint8_t* grey = smoothed_.ptr<uint8_t>(y);
    int32_t* index = point_index_.ptr<int32_t>(y);
    for (int x = kBorderPx; x < gradient_x_.cols - kBorderPx; ++x) {
      if (m[x] < min_squared_sobel_) {
        continue;
      }
      const Direction d = quantise(gx[x], gy[x]);
      const int offset = d.dy * stride + d.dx;
      const int32_t before = m[x - offset];
      const int32_t after = m[x + offset];
      if (!(m[x] > before && m[x] >= after)) {
        continue;
      }
      const float log_before = std::log(static_cast<float>(std::max<int32_t>(before, 1)));
      const float log_here = std::log(static_cast<float>(std::max<int32_t>(m[x], 1)));
      const float log_after = std::log(static_cast<float>(std::max<int32_t>(after, 1)));
      const float curvature = log_before - 2.0f * log_here + log_after;
      const float delta = curvature < 0.0f
                              ? std::clamp(0.5f * (log_before - log_after) / curvature, -0.5f, 0.5f)
                              : 0.0f;
      const int step_offset = kStepSampleDistancePx * (d.dy * smoothed_stride + d.dx);
      EdgePoint point;
      point.position = {static_cast<float>(x) + delta * static_cast<float>(d.dx),
                        static_cast<float>(y) + delta * static_cast<float>(d.dy)};
      point.gradient = {gx[x] / kSobelGain, gy[x] / kSobelGain};
      point.normal = point.gradient * (kSobelGain / std::sqrt(static_cast<float>(m[x])));
      point.step = static_cast<float>(grey[x + step_offset]) - grey[x - step_offset];
      point.pixel_x = x;
      point.pixel_y = y;
      index[x] = static_cast<int32_t>(points_.size());
      points_.push_back(point);
    }
  }
}

}  // namespace lineloc
