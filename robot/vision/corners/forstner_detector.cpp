#include "robot/vision/corners/forstner_detector.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

// foreach_target.h compiles this file once per instruction set; it must
// come before highway.h.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "robot/vision/corners/forstner_detector.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
// clang-format on

#include "robot/vision/simd/append_selected-inl.h"
#include "robot/vision/simd/for_each_span-inl.h"

HWY_BEFORE_NAMESPACE();
namespace lineloc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Moves the column sums down a row: adds the tensor entries h h^T of the
// row entering (h = g / 4, rounded down, so that a (2r+1)^2 window sum of
// 2^24 at most fits 32 bits for r <= 5) and subtracts those of the row
// leaving (if any): a at sums[x], b at sums[width + x], c at sums[2 width + x].
void UpdateColumns(const int16_t* entering_x, const int16_t* entering_y, const int16_t* leaving_x,
                   const int16_t* leaving_y, int width, int32_t* sums) {
  forEachSpan(hn::ScalableTag<int32_t>(), 0, width, [&](auto d, int x) {
    const hn::Rebind<int16_t, decltype(d)> d16;
    const auto load = [&](const int16_t* gradient) {
      return hn::ShiftRight<2>(hn::PromoteTo(d, hn::LoadU(d16, gradient + x)));
    };
    const auto hx = load(entering_x);
    const auto hy = load(entering_y);
    auto a = hn::LoadU(d, sums + x) + hx * hx;
    auto b = hn::LoadU(d, sums + width + x) + hx * hy;
    auto c = hn::LoadU(d, sums + 2 * width + x) + hy * hy;
    if (leaving_x != nullptr) {
      const auto lx = load(leaving_x);
      const auto ly = load(leaving_y);
      a = a - lx * lx;
      b = b - lx * ly;
      c = c - ly * ly;
    }
    hn::StoreU(a, d, sums + x);
    hn::StoreU(b, d, sums + width + x);
    hn::StoreU(c, d, sums + 2 * width + x);
  });
}

// w = det N / tr N for x in [radius, width - radius) from the column sums,
// kept where q = 4 det / tr^2 >= min_roundness (w >= min_roundness tr / 4)
// and 0 elsewhere. Returns the sum of w over the row before the roundness
// test; `peak` is the largest w kept.
template <int radius>
double WeightRowOfRadius(const int32_t* sums, int width, float min_roundness, float* weight,
                         float* peak) {
  // Stores the lanes of d at x; w before the roundness test and as kept.
  const auto weights_at = [&](auto d, int x, auto& kept) {
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
    const auto det = hn::Max(a * c - b * b, hn::Zero(d));
    const auto trace = hn::Max(a + c, hn::Set(d, 1.0f));
    // 1 / trace: the estimate and one Newton step, 2^-22 relative at worst.
    const auto estimate = hn::ApproximateReciprocal(trace);
    const auto w = det * (estimate * hn::NegMulAdd(trace, estimate, hn::Set(d, 2.0f)));
    kept = hn::IfThenElseZero(hn::Not(w < hn::Set(d, 0.25f * min_roundness) * trace), w);
    hn::StoreU(kept, d, weight + x);
    return w;
  };
  const hn::ScalableTag<float> d;
  const int lanes = static_cast<int>(hn::Lanes(d));
  auto total = hn::Zero(d);
  auto largest = hn::Zero(d);
  int x = radius;
  for (; x + lanes <= width - radius; x += lanes) {
    auto kept = hn::Zero(d);
    total = total + weights_at(d, x, kept);
    largest = hn::Max(largest, kept);
  }
  double sum = hn::GetLane(hn::SumOfLanes(d, total));
  float top = hn::GetLane(hn::MaxOfLanes(d, largest));
  if constexpr (hn::MaxLanes(decltype(d)()) > 1) {
    forEachSpan(hn::Half<decltype(d)>(), x, width - radius, [&](auto dh, int xh) {
      auto kept = hn::Zero(dh);
      sum += hn::GetLane(hn::SumOfLanes(dh, weights_at(dh, xh, kept)));
      top = std::max(top, hn::GetLane(hn::MaxOfLanes(dh, kept)));
    });
  }
  *peak = top;
  return sum;
}

// WeightRowOfRadius with the radius a constant, so that the box sums unroll.
double WeightRow(const int32_t* sums, int width, int radius, float min_roundness, float* weight,
                 float* peak) {
  switch (radius) {
    case 1:
      return WeightRowOfRadius<1>(sums, width, min_roundness, weight, peak);
    case 2:
      return WeightRowOfRadius<2>(sums, width, min_roundness, weight, peak);
    case 3:
      return WeightRowOfRadius<3>(sums, width, min_roundness, weight, peak);
    case 4:
      return WeightRowOfRadius<4>(sums, width, min_roundness, weight, peak);
    default:
      return WeightRowOfRadius<5>(sums, width, min_roundness, weight, peak);
  }
}

// The largest weight within `radius` columns: for x in [radius, width - radius).
void HorizontalMaximum(const float* weight, int width, int radius, float* maximum) {
  forEachSpan(hn::ScalableTag<float>(), radius, width - radius, [&](auto d, int x) {
    auto largest = hn::LoadU(d, weight + x - radius);
    for (int k = 1 - radius; k <= radius; ++k) {
      largest = hn::Max(largest, hn::LoadU(d, weight + x + k));
    }
    hn::StoreU(largest, d, maximum + x);
  });
}

// The columns x in [begin, end) where weight >= threshold and no weight in
// the window whose rows' horizontal maxima are `row_maxima` (the weight's own
// row first) is larger; returns their number (`xs` has kCompressSlack to spare).
int LocalMaxima(const float* weight, const float* const* row_maxima, int rows,
                const int32_t* columns, int begin, int end, float threshold, int32_t* xs) {
  size_t count = 0;
  forEachSpan(hn::ScalableTag<float>(), begin, end, [&](auto d, int x) {
    const auto here = hn::LoadU(d, weight + x);
    auto maximum =
        hn::AndNot(here < hn::LoadU(d, row_maxima[0] + x), hn::Not(here < hn::Set(d, threshold)));
    if (hn::AllFalse(d, maximum)) {
      return;
    }
    for (int row = 1; row < rows; ++row) {
      maximum = hn::AndNot(here < hn::LoadU(d, row_maxima[row] + x), maximum);
    }
    const hn::Rebind<int32_t, decltype(d)> di;
    count +=
        appendSelected(di, hn::LoadU(di, columns + x), hn::RebindMask(di, maximum), xs + count);
  });
  return static_cast<int>(count);
}

// `count` gradient values, scaled by `scale`, into floats.
void ScaleToFloat(const int16_t* gradient, int count, float scale, float* out) {
  forEachSpan(hn::ScalableTag<float>(), 0, count, [&](auto d, int i) {
    const hn::Rebind<int16_t, decltype(d)> d16;
    const hn::Rebind<int32_t, decltype(d)> di;
    hn::StoreU(
        hn::ConvertTo(d, hn::PromoteTo(di, hn::LoadU(d16, gradient + i))) * hn::Set(d, scale), d,
        out + i);
  });
}

// Over the lanes i of a refinement window with (u_i - cx)^2 + (v_i - cy)^2 <
// radius2: sums of g g^T and g g^T p, p = (u, v), into `sums` = (a, b, c,
// au, bu, bv, cv); returns how many lanes that is.
int WindowMoments(const float* gx, const float* gy, const float* u, const float* v, int count,
                  float cx, float cy, float radius2, double* sums) {
  const hn::ScalableTag<float> d;
  auto a = hn::Zero(d), b = a, c = a, au = a, bu = a, bv = a, cv = a;
  size_t pixels = 0;
  for (int i = 0; i < count; i += static_cast<int>(hn::Lanes(d))) {
    const auto pu = hn::LoadU(d, u + i);
    const auto pv = hn::LoadU(d, v + i);
    const auto du = pu - hn::Set(d, cx);
    const auto dv = pv - hn::Set(d, cy);
    const auto inside = du * du + dv * dv < hn::Set(d, radius2);
    pixels += hn::CountTrue(d, inside);
    const auto x = hn::IfThenElseZero(inside, hn::LoadU(d, gx + i));
    const auto y = hn::LoadU(d, gy + i);
    const auto xx = x * x, xy = x * y, yy = hn::IfThenElseZero(inside, y * y);
    a = a + xx;
    b = b + xy;
    c = c + yy;
    au = hn::MulAdd(xx, pu, au);
    bu = hn::MulAdd(xy, pu, bu);
    bv = hn::MulAdd(xy, pv, bv);
    cv = hn::MulAdd(yy, pv, cv);
  }
  int k = 0;
  for (const auto& sum : {a, b, c, au, bu, bv, cv}) {
    sums[k++] = hn::GetLane(hn::SumOfLanes(d, sum));
  }
  return static_cast<int>(pixels);
}

// sum over the window of (g^T (x - p))^2, x = (px, py).
double WindowResidual(const float* gx, const float* gy, const float* u, const float* v, int count,
                      float px, float py) {
  const hn::ScalableTag<float> d;
  auto total = hn::Zero(d);
  for (int i = 0; i < count; i += static_cast<int>(hn::Lanes(d))) {
    const auto along_normal = hn::LoadU(d, gx + i) * (hn::Set(d, px) - hn::LoadU(d, u + i)) +
                              hn::LoadU(d, gy + i) * (hn::Set(d, py) - hn::LoadU(d, v + i));
    total = hn::MulAdd(along_normal, along_normal, total);
  }
  return hn::GetLane(hn::SumOfLanes(d, total));
}

}  // namespace HWY_NAMESPACE
}  // namespace lineloc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lineloc {
namespace {

// The tensor sums (g / 4)(g / 4)^T.
constexpr double kGradientStep = 4.0;
constexpr int kMaxWindowRadiusPx = 5;
// w is evaluated on every kRowStep-th row.
constexpr int kRowStep = 2;

// The window lanes: a multiple of any target's vector length; the padding
// lanes have no gradient and lie outside every disc.
constexpr int kWindowLaneMultiple = 64;
constexpr float kPaddingOffsetPx = 1e4f;

// sum g g^T and sum g g^T p over pixels p = (u, v) of the window, relative
// to its centre.
struct GradientMoments {
  double a = 0.0, b = 0.0, c = 0.0;               // N = [a b; b c]
  double au = 0.0, bu = 0.0, bv = 0.0, cv = 0.0;  // sum g g^T p = (au + bv, bu + cv)
  int pixels = 0;

  Eigen::Matrix2d normal() const { return (Eigen::Matrix2d() << a, b, b, c).finished(); }
  Eigen::Vector2d rightSide() const { return {au + bv, bu + cv}; }
  GradientMoments operator-(const GradientMoments& o) const {
    return {a - o.a,   b - o.b,   c - o.c,   au - o.au,
            bu - o.bu, bv - o.bv, cv - o.cv, pixels - o.pixels};
  }
};

}  // namespace

HWY_EXPORT(UpdateColumns);
HWY_EXPORT(WeightRow);
HWY_EXPORT(HorizontalMaximum);
HWY_EXPORT(LocalMaxima);
HWY_EXPORT(ScaleToFloat);
HWY_EXPORT(WindowMoments);
HWY_EXPORT(WindowResidual);

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
  suppression_rows_.resize(2 * options.suppression_radius_px + 1);
  const int r = options.refine_radius_px;
  const int side = 2 * r + 1;
  const int lanes =
      (side * side + kWindowLaneMultiple - 1) / kWindowLaneMultiple * kWindowLaneMultiple;
  window_u_.assign(lanes, kPaddingOffsetPx);
  window_v_.assign(lanes, kPaddingOffsetPx);
  window_gx_.assign(lanes, 0.0f);
  window_gy_.assign(lanes, 0.0f);
  for (int i = 0; i < side * side; ++i) {
    window_u_[i] = static_cast<float>(i % side - r);
    window_v_[i] = static_cast<float>(i / side - r);
  }
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
  tensor_scale_ = kGradientStep * kGradientStep / (static_cast<double>(gain) * gain);
  column_sums_.assign(3 * static_cast<size_t>(size.width), 0);
  // Every ring row is written before it is read (rows of w below the floor
  // stand in as zero_row_ for their maxima).
  weight_rows_.resize(static_cast<size_t>(weightRingRows()) * size.width);
  row_maximum_rows_.resize(weight_rows_.size());
  row_peaks_.assign(weightRingRows(), 0.0f);
  zero_row_.assign(size.width, 0.0f);
  row_candidates_.resize(static_cast<size_t>(size.width) + kCompressSlack);
  column_numbers_.resize(size.width);
  std::iota(column_numbers_.begin(), column_numbers_.end(), 0);
  weight_sum_ = 0.0;
  candidates_.clear();
  corners_.clear();
}

// Window sums by running column sums (add the row entering, drop the row
// leaving) and a (2r+1)-tap horizontal sum; w and q straight from them.
// Row y completes the window of w row y - r.
void ForstnerDetector::addRow(int y, const cv::Mat& gradient_x, const cv::Mat& gradient_y) {
  const int r = options_.window_radius_px;
  const int leaving = y - 2 * r - 1;
  HWY_DYNAMIC_DISPATCH(UpdateColumns)
  (gradient_x.ptr<int16_t>(y), gradient_y.ptr<int16_t>(y),
   leaving >= 0 ? gradient_x.ptr<int16_t>(leaving) : nullptr,
   leaving >= 0 ? gradient_y.ptr<int16_t>(leaving) : nullptr, size_.width, column_sums_.data());
  const int centre = y - r;
  if (centre < r) {
    return;
  }
  float& peak = row_peaks_[centre % weightRingRows()];
  if (centre % kRowStep != 0) {
    peak = 0.0f;
    suppressNonMaxima(centre - options_.suppression_radius_px);
    return;
  }
  float* w = weightRow(centre);
  std::fill_n(w, r, 0.0f);
  std::fill_n(w + size_.width - r, r, 0.0f);
  weight_sum_ += HWY_DYNAMIC_DISPATCH(WeightRow)(
      column_sums_.data(), size_.width, r, static_cast<float>(options_.min_roundness), w, &peak);
  // A row without a candidate can stand in as zeros for the row maxima.
  if (peak >= candidateFloor()) {
    HWY_DYNAMIC_DISPATCH(HorizontalMaximum)
    (w, size_.width, options_.suppression_radius_px, rowMaximumRow(centre));
  } else {
    peak = 0.0f;
  }
  suppressNonMaxima(centre - options_.suppression_radius_px);
}

void ForstnerDetector::finish(const cv::Mat& gradient_x, const cv::Mat& gradient_y) {
  // w is 0 within r of the bottom; the last rows' maxima need those zeros.
  const int s = options_.suppression_radius_px;
  for (int centre = std::max(0, size_.height - options_.window_radius_px);
       centre < size_.height + s; ++centre) {
    std::fill_n(weightRow(centre), size_.width, 0.0f);
    row_peaks_[centre % weightRingRows()] = 0.0f;
    suppressNonMaxima(centre - s);
  }
  const float min_weight = candidateFloor();
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
      corner.weight = static_cast<float>(candidate.weight * tensor_scale_);
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

float* ForstnerDetector::rowMaximumRow(int y) {
  return row_maximum_rows_.data() + static_cast<size_t>(y % weightRingRows()) * size_.width;
}

// max(min_weight, weight_factor x mean w) in tensor units, the mean over the
// whole image with w = 0 in the rows still to come: a lower bound of the
// final threshold until the last row is in, and the threshold then.
float ForstnerDetector::candidateFloor() const {
  const int sampled_rows = (size_.height + kRowStep - 1) / kRowStep;
  const double mean_weight = weight_sum_ / (static_cast<double>(size_.width) * sampled_rows);
  return static_cast<float>(
      std::max(options_.min_weight / tensor_scale_, options_.weight_factor * mean_weight));
}

// Local maxima of w over (2s+1)^2 in row y, w >= candidateFloor(), away from
// the border: w against the maxima over 2s+1 columns of the 2s+1 rows
// around, all by SIMD. Rows whose w stays below the floor take part as
// zeros.
void ForstnerDetector::suppressNonMaxima(int y) {
  const int s = options_.suppression_radius_px;
  const int margin = std::max({options_.window_radius_px, options_.refine_radius_px, s}) + 1;
  const float floor = candidateFloor();
  if (y < margin || y >= size_.height - margin || row_peaks_[y % weightRingRows()] < floor) {
    return;
  }
  const auto maxima_of = [&](int row) -> const float* {
    return row_peaks_[row % weightRingRows()] > 0.0f ? rowMaximumRow(row) : zero_row_.data();
  };
  suppression_rows_[0] = maxima_of(y);
  for (int v = 1; v <= s; ++v) {
    suppression_rows_[2 * v - 1] = maxima_of(y - v);
    suppression_rows_[2 * v] = maxima_of(y + v);
  }
  const float* w = weightRow(y);
  const int count = HWY_DYNAMIC_DISPATCH(LocalMaxima)(
      w, suppression_rows_.data(), static_cast<int>(suppression_rows_.size()),
      column_numbers_.data(), margin, size_.width - margin, floor, row_candidates_.data());
  for (int i = 0; i < count; ++i) {
    const int x = row_candidates_[i];
    candidates_.push_back({x, y, w[x]});
  }
}

bool ForstnerDetector::refine(const cv::Mat& gradient_x, const cv::Mat& gradient_y,
                              const Candidate& candidate, ForstnerCorner& corner) {
  const int r = options_.refine_radius_px;
  const int side = 2 * r + 1;
  const float inverse_gain = 1.0f / gain_;
  for (int v = -r; v <= r; ++v) {
    const size_t row = static_cast<size_t>(v + r) * side;
    HWY_DYNAMIC_DISPATCH(ScaleToFloat)
    (gradient_x.ptr<int16_t>(candidate.y + v) + candidate.x - r, side, inverse_gain,
     window_gx_.data() + row);
    HWY_DYNAMIC_DISPATCH(ScaleToFloat)
    (gradient_y.ptr<int16_t>(candidate.y + v) + candidate.x - r, side, inverse_gain,
     window_gy_.data() + row);
  }
  const int lanes = static_cast<int>(window_u_.size());
  const auto moments = [&](const Eigen::Vector2d& centre, double radius) {
    double sums[7];
    const int pixels = HWY_DYNAMIC_DISPATCH(WindowMoments)(
        window_gx_.data(), window_gy_.data(), window_u_.data(), window_v_.data(), lanes,
        static_cast<float>(centre.x()), static_cast<float>(centre.y()),
        static_cast<float>(radius * radius), sums);
    return GradientMoments{sums[0], sums[1], sums[2], sums[3], sums[4], sums[5], sums[6], pixels};
  };
  const auto solve = [r](const GradientMoments& m, Eigen::Vector2d& x, Eigen::Matrix2d& inverse) {
    const Eigen::Matrix2d normal = m.normal();
    if (!(normal.determinant() > 0.0) || m.pixels < 3) {
      return false;
    }
    inverse = normal.inverse();
    x = inverse * m.rightSide();
    return std::abs(x.x()) <= r && std::abs(x.y()) <= r;
  };
  const GradientMoments window = moments(Eigen::Vector2d::Zero(), 2.0 * side);
  Eigen::Vector2d first, position;
  Eigen::Matrix2d inverse;
  if (!solve(window, first, inverse)) {
    return false;
  }
  // The flanks: the window less the pixels within core_radius of `first`.
  if (!solve(window - moments(first, options_.core_radius_px), position, inverse)) {
    return false;
  }
  const double residual = HWY_DYNAMIC_DISPATCH(WindowResidual)(
      window_gx_.data(), window_gy_.data(), window_u_.data(), window_v_.data(), lanes,
      static_cast<float>(position.x()), static_cast<float>(position.y()));
  const double sigma0_squared = residual / (side * side - 2);
  corner.position = (position + Eigen::Vector2d(candidate.x, candidate.y)).cast<float>();
  corner.covariance = (sigma0_squared * inverse).cast<float>();
  return true;
}

}  // namespace lineloc
#endif  // HWY_ONCE
