#include "robot/vision/corners/forstner_detector.h"

#include <Eigen/Dense>
#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace lineloc {
namespace {

// Sobel 3x3 gives 8 x the gradient.
constexpr float kInverseSobelGain = 1.0f / 8.0f;
// Below this tensor trace, (grey levels / px)^2 summed over the window, w is 0.
constexpr float kMinTrace = 1e-3f;

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
}

void ForstnerDetector::detect(const cv::Mat& gradient_x, const cv::Mat& gradient_y) {
  corners_.clear();
  const float mean_weight = computeWeights(gradient_x, gradient_y);
  const float min_weight = std::max(static_cast<float>(options_.min_weight),
                                    static_cast<float>(options_.weight_factor) * mean_weight);
  collectCandidates(min_weight);
  std::sort(candidates_.begin(), candidates_.end(),
            [](const Candidate& a, const Candidate& b) { return a.weight > b.weight; });
  for (const Candidate& candidate : candidates_) {
    if (static_cast<int>(corners_.size()) >= options_.max_corners) {
      break;
    }
    ForstnerCorner corner;
    if (refine(gradient_x, gradient_y, candidate.x, candidate.y, corner)) {
      corner.weight = candidate.weight;
      corners_.push_back(corner);
    }
  }
}

void ForstnerDetector::computeProducts(const cv::Mat& gradient_x, const cv::Mat& gradient_y) {
  const size_t plane = gradient_x.total();
  products_.resize(3 * plane);
  float* xx = products_.data();
  float* xy = xx + plane;
  float* yy = xy + plane;
  for (int y = 0; y < gradient_x.rows; ++y) {
    const int16_t* gx = gradient_x.ptr<int16_t>(y);
    const int16_t* gy = gradient_y.ptr<int16_t>(y);
    const size_t row = static_cast<size_t>(y) * gradient_x.cols;
    for (int x = 0; x < gradient_x.cols; ++x) {
      const float fx = gx[x] * kInverseSobelGain;
      const float fy = gy[x] * kInverseSobelGain;
      xx[row + x] = fx * fx;
      xy[row + x] = fx * fy;
      yy[row + x] = fy * fy;
    }
  }
}

// Window sums by running column sums (add the row entering, drop the row
// leaving) and a (2r+1)-tap horizontal sum; w and q straight from them.
float ForstnerDetector::computeWeights(const cv::Mat& gradient_x, const cv::Mat& gradient_y) {
  computeProducts(gradient_x, gradient_y);
  const int width = gradient_x.cols;
  const int height = gradient_x.rows;
  const int r = options_.window_radius_px;
  const size_t plane = gradient_x.total();
  weight_.create(gradient_x.size(), CV_32F);
  std::fill_n(weight_.ptr<float>(), weight_.total(), 0.0f);
  column_sums_.assign(3 * static_cast<size_t>(width), 0.0f);
  tensor_row_.resize(3 * static_cast<size_t>(width));
  for (int v = 0; v < std::min(2 * r, height); ++v) {
    addRow(v, 1.0f, plane, width);
  }
  const float min_roundness = static_cast<float>(options_.min_roundness);
  double weight_sum = 0.0;
  for (int y = r; y < height - r; ++y) {
    addRow(y + r, 1.0f, plane, width);
    std::fill(tensor_row_.begin(), tensor_row_.end(), 0.0f);
    for (int c = 0; c < 3; ++c) {
      const float* column = column_sums_.data() + c * width;
      float* tensor = tensor_row_.data() + c * width;
      for (int k = -r; k <= r; ++k) {
        for (int x = r; x < width - r; ++x) {
          tensor[x] += column[x + k];
        }
      }
    }
    const float* a = tensor_row_.data();
    const float* b = a + width;
    const float* c = b + width;
    float* w = weight_.ptr<float>(y);
    float row_sum = 0.0f;
    for (int x = r; x < width - r; ++x) {
      const float trace = a[x] + c[x];
      const float det = a[x] * c[x] - b[x] * b[x];
      const float weight = det / std::max(trace, kMinTrace);
      row_sum += weight;
      w[x] = 4.0f * det >= min_roundness * trace * trace ? weight : 0.0f;
    }
    weight_sum += row_sum;
    addRow(y - r, -1.0f, plane, width);
  }
  return static_cast<float>(weight_sum / static_cast<double>(plane));
}

void ForstnerDetector::addRow(int y, float sign, size_t plane, int width) {
  for (int c = 0; c < 3; ++c) {
    const float* row = products_.data() + c * plane + static_cast<size_t>(y) * width;
    float* column = column_sums_.data() + c * width;
    for (int x = 0; x < width; ++x) {
      column[x] += sign * row[x];
    }
  }
}

// Local maxima of w over (2s+1)^2, among the pixels above the threshold.
void ForstnerDetector::collectCandidates(float min_weight) {
  candidates_.clear();
  const int s = options_.suppression_radius_px;
  const int margin = std::max({options_.window_radius_px, options_.refine_radius_px, s}) + 1;
  for (int y = margin; y < weight_.rows - margin; ++y) {
    const float* w = weight_.ptr<float>(y);
    for (int x = margin; x < weight_.cols - margin; ++x) {
      if (w[x] >= min_weight && isLocalMaximum(x, y)) {
        candidates_.push_back({x, y, w[x]});
      }
    }
  }
}

bool ForstnerDetector::isLocalMaximum(int x, int y) const {
  const int s = options_.suppression_radius_px;
  const float here = weight_.at<float>(y, x);
  for (int v = y - s; v <= y + s; ++v) {
    const float* w = weight_.ptr<float>(v);
    for (int u = x - s; u <= x + s; ++u) {
      if (w[u] > here) {
        return false;
      }
    }
  }
  return true;
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
