#include "robot/vision/corners/forstner_detector.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

// foreach_target.h compiles this file once per instruction set; it must
// come before highway.h.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "robot/vision/corners/forstner_detector.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
// clang-format on

#include "robot/vision/simd/for_each_span-inl.h"

HWY_BEFORE_NAMESPACE();
namespace lineloc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Adds (or subtracts) one row's tensor entries round(g g^T / 16) to the
// column sums: a at sums[x], b at sums[width + x], c at sums[2 width + x].
void AccumulateColumns(const int16_t* gradient_x, const int16_t* gradient_y, int width,
                       bool subtract, int32_t* sums) {
  forEachSpan(hn::ScalableTag<int32_t>(), 0, width, [&](auto d, int x) {
    const hn::Rebind<int16_t, decltype(d)> d16;
    const auto gx = hn::PromoteTo(d, hn::LoadU(d16, gradient_x + x));
    const auto gy = hn::PromoteTo(d, hn::LoadU(d16, gradient_y + x));
    const auto half = hn::Set(d, 8);
    const auto add = [&](decltype(gx) product, int32_t* column) {
      const auto rounded = hn::ShiftRight<4>(product + half);
      const auto sum = hn::LoadU(d, column + x);
      hn::StoreU(subtract ? sum - rounded : sum + rounded, d, column + x);
    };
    add(gx * gx, sums);
    add(gx * gy, sums + width);
    add(gy * gy, sums + 2 * width);
  });
}

// w = det N / tr N (times `scale`) for x in [radius, width - radius) from the
// column sums, kept where q = 4 det / tr^2 >= min_roundness and 0 elsewhere.
// Returns the sum of w over the row before the roundness test.
double WeightRow(const int32_t* sums, int width, int radius, float min_roundness, float scale,
                 float* weight) {
  // Stores the lanes of d at x, returns w before the roundness test.
  const auto weights_at = [&](auto d, int x) {
    const hn::Rebind<int32_t, decltype(d)> di;
    const auto box = [&](const int32_t* column) {
      auto sum = hn::LoadU(di, column + x - radius);
      for (int k = 1 - radius; k <= radius; ++k) {
        sum = sum + hn::LoadU(di, column + x + k);
      }
      return hn::ConvertTo(d, sum);
    };
    const auto a = box(sums);
    const auto b = box(sums + width);
    const auto c = box(sums + 2 * width);
    const auto det = a * c - b * b;
    const auto trace = a + c;
    const auto w = det / hn::Max(trace, hn::Set(d, 1.0f)) * hn::Set(d, scale);
    const auto round = hn::Not(hn::Set(d, 4.0f) * det < hn::Set(d, min_roundness) * trace * trace);
    hn::StoreU(hn::IfThenElseZero(round, w), d, weight + x);
    return w;
  };
  const hn::ScalableTag<float> d;
  const hn::CappedTag<float, 1> d1;
  const int lanes = static_cast<int>(hn::Lanes(d));
  auto total = hn::Zero(d);
  int x = radius;
  for (; x + lanes <= width - radius; x += lanes) {
    total = total + weights_at(d, x);
  }
  double sum = hn::GetLane(hn::SumOfLanes(d, total));
  for (; x < width - radius; ++x) {
    sum += hn::GetLane(weights_at(d1, x));
  }
  return sum;
}

// The columns x in [begin, end) where weight >= threshold and no weight
// within `radius` columns is larger (the row's part of the suppression);
// returns their number.
int RowMaxima(const float* weight, int begin, int end, float threshold, int radius, int32_t* xs) {
  size_t count = 0;
  forEachSpan(hn::ScalableTag<float>(), begin, end, [&](auto d, int x) {
    const auto here = hn::LoadU(d, weight + x);
    auto maximum = hn::Not(here < hn::Set(d, threshold));
    for (int k = 1; k <= radius && !hn::AllFalse(d, maximum); ++k) {
      maximum = hn::AndNot(here < hn::LoadU(d, weight + x - k), maximum);
      maximum = hn::AndNot(here < hn::LoadU(d, weight + x + k), maximum);
    }
    if (hn::AllFalse(d, maximum)) {
      return;
    }
    const hn::Rebind<int32_t, decltype(d)> di;
    count += hn::CompressBlendedStore(hn::Iota(di, x), hn::RebindMask(di, maximum), di, xs + count);
  });
  return static_cast<int>(count);
}

}  // namespace HWY_NAMESPACE
}  // namespace lineloc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lineloc {
namespace {

// The tensor sums products g g^T / 2^4.
constexpr float kProductScale = 16.0f;
constexpr int kMaxWindowRadiusPx = 5;

// sum g g^T (1, u, v, u^2, uv, v^2) over pixels p = (u, v) relative to the
// window centre: N, sum g g^T p and sum p^T g g^T p.
struct GradientMoments {
  double a = 0.0, b = 0.0, c = 0.0;               // N = [a b; b c]
  double au = 0.0, bu = 0.0, bv = 0.0, cv = 0.0;  // sum g g^T p = (au + bv, bu + cv)
  double auu = 0.0, buv = 0.0, cvv = 0.0;         // sum p^T g g^T p = auu + 2 buv + cvv
  int pixels = 0;

  void add(double gx, double gy, double u, double v, double sign) {
    const double xx = sign * gx * gx, xy = sign * gx * gy, yy = sign * gy * gy;
    a += xx;
    b += xy;
    c += yy;
    au += xx * u;
    bu += xy * u;
    bv += xy * v;
    cv += yy * v;
    auu += xx * u * u;
    buv += xy * u * v;
    cvv += yy * v * v;
    pixels += sign > 0.0 ? 1 : -1;
  }
  Eigen::Matrix2d normal() const { return (Eigen::Matrix2d() << a, b, b, c).finished(); }
  Eigen::Vector2d rightSide() const { return {au + bv, bu + cv}; }
  // sum (g^T (x - p))^2 over the window.
  double residual(const Eigen::Vector2d& x) const {
    return x.dot(normal() * x) - 2.0 * x.dot(rightSide()) + auu + 2.0 * buv + cvv;
  }
};

// Pixels p = (u, v) relative to a window centre, u in [u0, u1], v in [v0, v1].
struct PixelBox {
  int u0, u1, v0, v1;
};

// Visits the pixels of `box` around (x, y) for which within(u, v) holds, with
// their gradient in grey levels per px.
template <typename Within, typename Visit>
void forEachPixel(const cv::Mat& gradient_x, const cv::Mat& gradient_y, float gain, int x, int y,
                  const PixelBox& box, Within within, Visit visit) {
  const double inverse_gain = 1.0 / gain;
  for (int v = box.v0; v <= box.v1; ++v) {
    const int16_t* gx = gradient_x.ptr<int16_t>(y + v);
    const int16_t* gy = gradient_y.ptr<int16_t>(y + v);
    for (int u = box.u0; u <= box.u1; ++u) {
      if (within(u, v)) {
        visit(gx[x + u] * inverse_gain, gy[x + u] * inverse_gain, u, v);
      }
    }
  }
}

}  // namespace

HWY_EXPORT(AccumulateColumns);
HWY_EXPORT(WeightRow);
HWY_EXPORT(RowMaxima);

ForstnerDetector::ForstnerDetector(const ForstnerOptions& options) : options_(options) {
  if (options.window_radius_px < 1 || options.window_radius_px > kMaxWindowRadiusPx ||
      options.suppression_radius_px < 1 || options.refine_radius_px < 1 ||
      !(options.core_radius_px >= 0.0) ||
      !(options.min_roundness >= 0.0 && options.min_roundness <= 1.0) ||
      !(options.weight_factor >= 0.0) || !(options.min_weight > 0.0) || options.max_corners < 0) {
    throw std::invalid_argument(
        "Förstner: window radius in [1, 5], other radii >= 1, min_roundness in [0, 1], "
        "weight_factor >= 0, min_weight > 0, max_corners >= 0");
  }
  const int s = options.suppression_radius_px;
  for (int dy = -s; dy <= s; ++dy) {
    for (int dx = -s; dx <= s; ++dx) {
      if (dy != 0) {
        neighbourhood_.push_back({dx, dy});
      }
    }
  }
  std::stable_sort(neighbourhood_.begin(), neighbourhood_.end(), [](Offset a, Offset b) {
    return a.dx * a.dx + a.dy * a.dy < b.dx * b.dx + b.dy * b.dy;
  });
  suppression_rows_.resize(2 * s + 1);
}

void ForstnerDetector::detect(const cv::Mat& gradient_x, const cv::Mat& gradient_y, float gain) {
  begin(gradient_x.size(), gain);
  for (int y = 0; y < gradient_x.rows; ++y) {
    addRow(y, gradient_x, gradient_y);
  }
  finish(gradient_x, gradient_y);
}

void ForstnerDetector::begin(cv::Size size, float gain) {
  size_ = size;
  gain_ = gain;
  column_sums_.assign(3 * static_cast<size_t>(size.width), 0);
  weight_rows_.assign(static_cast<size_t>(weightRingRows()) * size.width, 0.0f);
  row_candidates_.resize(size.width);
  weight_sum_ = 0.0;
  candidates_.clear();
  corners_.clear();
}

// Window sums by running column sums (add the row entering, drop the row
// leaving) and a (2r+1)-tap horizontal sum; w and q straight from them.
// Row y completes the window of w row y - r.
void ForstnerDetector::addRow(int y, const cv::Mat& gradient_x, const cv::Mat& gradient_y) {
  const int r = options_.window_radius_px;
  const auto accumulate = [&](int row, bool subtract) {
    HWY_DYNAMIC_DISPATCH(AccumulateColumns)
    (gradient_x.ptr<int16_t>(row), gradient_y.ptr<int16_t>(row), size_.width, subtract,
     column_sums_.data());
  };
  accumulate(y, false);
  const int centre = y - r;
  if (centre < r) {
    return;
  }
  float* w = weightRow(centre);
  std::fill_n(w, r, 0.0f);
  std::fill_n(w + size_.width - r, r, 0.0f);
  weight_sum_ += HWY_DYNAMIC_DISPATCH(WeightRow)(column_sums_.data(), size_.width, r,
                                                 static_cast<float>(options_.min_roundness),
                                                 kProductScale / (gain_ * gain_), w);
  accumulate(centre - r, true);
  suppressNonMaxima(centre - options_.suppression_radius_px);
}

void ForstnerDetector::finish(const cv::Mat& gradient_x, const cv::Mat& gradient_y) {
  // w is 0 within r of the bottom; the last rows' maxima need those zeros.
  const int s = options_.suppression_radius_px;
  for (int centre = std::max(0, size_.height - options_.window_radius_px);
       centre < size_.height + s; ++centre) {
    std::fill_n(weightRow(centre), size_.width, 0.0f);
    suppressNonMaxima(centre - s);
  }
  const double mean_weight = weight_sum_ / (static_cast<double>(size_.width) * size_.height);
  const float min_weight =
      static_cast<float>(std::max(options_.min_weight, options_.weight_factor * mean_weight));
  std::erase_if(candidates_,
                [min_weight](const Candidate& candidate) { return candidate.weight < min_weight; });
  std::sort(candidates_.begin(), candidates_.end(),
            [](const Candidate& a, const Candidate& b) { return a.weight > b.weight; });
  for (const Candidate& candidate : candidates_) {
    if (static_cast<int>(corners_.size()) >= options_.max_corners) {
      break;
    }
    ForstnerCorner corner;
    if (refine(gradient_x, gradient_y, candidate, corner)) {
      corner.weight = candidate.weight;
      corners_.push_back(corner);
    }
  }
}

int ForstnerDetector::weightRingRows() const {
  return 2 * options_.suppression_radius_px + 1;
}

float* ForstnerDetector::weightRow(int y) {
  return weight_rows_.data() + static_cast<size_t>(y % weightRingRows()) * size_.width;
}

// Local maxima of w over (2s+1)^2 in row y, w >= min_weight (the threshold
// relative to the mean w waits for the last row), away from the border.
// The row's own neighbours are compared by SIMD, the other rows' nearest
// first: off a maximum, one of them is usually larger.
void ForstnerDetector::suppressNonMaxima(int y) {
  const int s = options_.suppression_radius_px;
  const int margin = std::max({options_.window_radius_px, options_.refine_radius_px, s}) + 1;
  if (y < margin || y >= size_.height - margin) {
    return;
  }
  for (int v = -s; v <= s; ++v) {
    suppression_rows_[v + s] = weightRow(y + v);
  }
  const float* w = suppression_rows_[s];
  const int count = HWY_DYNAMIC_DISPATCH(RowMaxima)(w, margin, size_.width - margin,
                                                    static_cast<float>(options_.min_weight), s,
                                                    row_candidates_.data());
  for (int i = 0; i < count; ++i) {
    const int x = row_candidates_[i];
    const float here = w[x];
    const bool maximum =
        std::none_of(neighbourhood_.begin(), neighbourhood_.end(), [&](const Offset& offset) {
          return suppression_rows_[offset.dy + s][x + offset.dx] > here;
        });
    if (maximum) {
      candidates_.push_back({x, y, here});
    }
  }
}

bool ForstnerDetector::refine(const cv::Mat& gradient_x, const cv::Mat& gradient_y,
                              const Candidate& candidate, ForstnerCorner& corner) const {
  const float gain = gain_;
  const int r = options_.refine_radius_px;
  const auto everywhere = [](int, int) { return true; };
  GradientMoments window;
  forEachPixel(gradient_x, gradient_y, gain, candidate.x, candidate.y, {-r, r, -r, r}, everywhere,
               [&](double gx, double gy, int u, int v) { window.add(gx, gy, u, v, 1.0); });
  const auto solve = [r](const GradientMoments& moments, Eigen::Vector2d& x,
                         Eigen::Matrix2d& inverse) {
    const Eigen::Matrix2d normal = moments.normal();
    if (!(normal.determinant() > 0.0) || moments.pixels < 3) {
      return false;
    }
    inverse = normal.inverse();
    x = inverse * moments.rightSide();
    return std::abs(x.x()) <= r && std::abs(x.y()) <= r;
  };
  Eigen::Vector2d first, position;
  Eigen::Matrix2d inverse;
  if (!solve(window, first, inverse)) {
    return false;
  }
  // The flanks: the window less the pixels within core_radius of `first`.
  const double core = options_.core_radius_px;
  const PixelBox core_box{std::max(-r, static_cast<int>(std::ceil(first.x() - core))),
                          std::min(r, static_cast<int>(std::floor(first.x() + core))),
                          std::max(-r, static_cast<int>(std::ceil(first.y() - core))),
                          std::min(r, static_cast<int>(std::floor(first.y() + core)))};
  GradientMoments flanks = window;
  forEachPixel(
      gradient_x, gradient_y, gain, candidate.x, candidate.y, core_box,
      [&](int u, int v) { return (Eigen::Vector2d(u, v) - first).squaredNorm() < core * core; },
      [&](double gx, double gy, int u, int v) { flanks.add(gx, gy, u, v, -1.0); });
  if (!solve(flanks, position, inverse)) {
    return false;
  }
  const int window_pixels = (2 * r + 1) * (2 * r + 1);
  const double sigma0_squared = std::max(0.0, window.residual(position)) / (window_pixels - 2);
  corner.position = (position + Eigen::Vector2d(candidate.x, candidate.y)).cast<float>();
  corner.covariance = (sigma0_squared * inverse).cast<float>();
  return true;
}

}  // namespace lineloc
#endif  // HWY_ONCE
