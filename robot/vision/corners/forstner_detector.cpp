#include "robot/vision/corners/forstner_detector.h"

#include <Eigen/Dense>
#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace lineloc {
namespace {

// Sobel 3x3 gives 8 x the gradient; products carry 64 x.
constexpr float kInverseSobelGainSquared = 1.0f / 64.0f;
constexpr float kInverseSobelGain = 1.0f / 8.0f;

}  // namespace

ForstnerDetector::ForstnerDetector(const ForstnerOptions& options) : options_(options) {
  if (options.window_radius_px < 1 || options.suppression_radius_px < 1 ||
      options.refine_radius_px < 1 || !(options.core_radius_px >= 0.0) ||
      !(options.min_roundness >= 0.0 && options.min_roundness <= 1.0) ||
      !(options.weight_factor >= 0.0) || !(options.min_weight > 0.0) || options.max_corners < 0) {
    throw std::invalid_argument(
        "Förstner: radii >= 1, min_roundness in [0, 1], weight_factor >= 0, min_weight > 0, "
        "max_corners >= 0");
  }
  const int side = 2 * options.suppression_radius_px + 1;
  suppression_kernel_ = cv::Mat::ones(side, side, CV_8U);
}

void ForstnerDetector::detect(const cv::Mat& gradient_x, const cv::Mat& gradient_y) {
  corners_.clear();
  computeTensor(gradient_x, gradient_y);
  const float mean_weight = computeWeights();
  const float min_weight = std::max(static_cast<float>(options_.min_weight),
                                    static_cast<float>(options_.weight_factor) * mean_weight);
  cv::dilate(weight_, dilated_, suppression_kernel_);
  const int margin = std::max(options_.window_radius_px, options_.refine_radius_px) + 1;
  for (int y = margin; y < weight_.rows - margin; ++y) {
    const float* w = weight_.ptr<float>(y);
    const float* w_max = dilated_.ptr<float>(y);
    for (int x = margin; x < weight_.cols - margin; ++x) {
      ForstnerCorner corner;
      if (w[x] >= min_weight && w[x] == w_max[x] && refine(gradient_x, gradient_y, x, y, corner)) {
        corner.weight = w[x];
        corners_.push_back(corner);
      }
    }
  }
  std::sort(corners_.begin(), corners_.end(),
            [](const ForstnerCorner& a, const ForstnerCorner& b) { return a.weight > b.weight; });
  if (static_cast<int>(corners_.size()) > options_.max_corners) {
    corners_.resize(options_.max_corners);
  }
}

void ForstnerDetector::computeTensor(const cv::Mat& gradient_x, const cv::Mat& gradient_y) {
  products_.create(gradient_x.size(), CV_32FC3);
  for (int y = 0; y < gradient_x.rows; ++y) {
    const int16_t* gx = gradient_x.ptr<int16_t>(y);
    const int16_t* gy = gradient_y.ptr<int16_t>(y);
    float* p = products_.ptr<float>(y);
    for (int x = 0; x < gradient_x.cols; ++x) {
      const float fx = gx[x];
      const float fy = gy[x];
      p[3 * x] = fx * fx * kInverseSobelGainSquared;
      p[3 * x + 1] = fx * fy * kInverseSobelGainSquared;
      p[3 * x + 2] = fy * fy * kInverseSobelGainSquared;
    }
  }
  const int side = 2 * options_.window_radius_px + 1;
  cv::boxFilter(products_, tensor_, CV_32F, cv::Size(side, side), cv::Point(-1, -1), false);
}

float ForstnerDetector::computeWeights() {
  weight_.create(tensor_.size(), CV_32F);
  const float min_roundness = static_cast<float>(options_.min_roundness);
  double weight_sum = 0.0;
  for (int y = 0; y < tensor_.rows; ++y) {
    const float* n = tensor_.ptr<float>(y);
    float* w = weight_.ptr<float>(y);
    float row_sum = 0.0f;
    for (int x = 0; x < tensor_.cols; ++x) {
      const float a = n[3 * x];
      const float b = n[3 * x + 1];
      const float c = n[3 * x + 2];
      const float trace = a + c;
      const float det = a * c - b * b;
      const float weight = trace > 0.0f ? det / trace : 0.0f;
      row_sum += weight;
      w[x] = (4.0f * det >= min_roundness * trace * trace && trace > 0.0f) ? weight : 0.0f;
    }
    weight_sum += row_sum;
  }
  return static_cast<float>(weight_sum / static_cast<double>(tensor_.total()));
}

// Normal equations of the gradient-line intersection over the pixels of the
// (2r+1)^2 window at (x, y) that lie at least `core_px` from `core`.
struct GradientLines {
  Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
  Eigen::Vector2d right_side = Eigen::Vector2d::Zero();
  int pixels = 0;
};

template <typename Visit>
void forEachGradient(const cv::Mat& gradient_x, const cv::Mat& gradient_y, int x, int y, int r,
                     const Eigen::Vector2d& core, double core_px, Visit visit) {
  const double core_squared = core_px * core_px;
  for (int v = y - r; v <= y + r; ++v) {
    const int16_t* gx = gradient_x.ptr<int16_t>(v);
    const int16_t* gy = gradient_y.ptr<int16_t>(v);
    for (int u = x - r; u <= x + r; ++u) {
      const Eigen::Vector2d p(u, v);
      if ((p - core).squaredNorm() >= core_squared) {
        visit(Eigen::Vector2d(gx[u] * kInverseSobelGain, gy[u] * kInverseSobelGain), p);
      }
    }
  }
}

bool ForstnerDetector::refine(const cv::Mat& gradient_x, const cv::Mat& gradient_y, int x, int y,
                              ForstnerCorner& corner) const {
  const int r = options_.refine_radius_px;
  Eigen::Vector2d position(x, y);
  double core_px = 0.0;
  Eigen::Matrix2d inverse;
  int pixels = 0;
  for (int pass = 0; pass < 2; ++pass) {
    Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
    Eigen::Vector2d right_side = Eigen::Vector2d::Zero();
    pixels = 0;
    forEachGradient(gradient_x, gradient_y, x, y, r, position, core_px,
                    [&](const Eigen::Vector2d& g, const Eigen::Vector2d& p) {
                      const Eigen::Matrix2d ggT = g * g.transpose();
                      normal += ggT;
                      right_side += ggT * p;
                      ++pixels;
                    });
    if (!(normal.determinant() > 0.0) || pixels < 3) {
      return false;
    }
    inverse = normal.inverse();
    position = inverse * right_side;
    if (std::abs(position.x() - x) > r || std::abs(position.y() - y) > r) {
      return false;
    }
    core_px = options_.core_radius_px;
  }
  double residual_sum = 0.0;
  forEachGradient(gradient_x, gradient_y, x, y, r, position, 0.0,
                  [&](const Eigen::Vector2d& g, const Eigen::Vector2d& p) {
                    const double residual = g.dot(position - p);
                    residual_sum += residual * residual;
                  });
  const int window_pixels = (2 * r + 1) * (2 * r + 1);
  corner.position = position.cast<float>();
  corner.covariance = (residual_sum / (window_pixels - 2) * inverse).cast<float>();
  return true;
}

}  // namespace lineloc
