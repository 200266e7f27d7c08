#include "robot/vision/edges/gaussian_smoother.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

// foreach_target.h compiles this file once per instruction set; it must
// come before highway.h.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "robot/vision/edges/gaussian_smoother.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
// clang-format on

#include "robot/vision/simd/for_each_span-inl.h"

HWY_BEFORE_NAMESPACE();
namespace lineloc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// t(x) = sum_k w_k row_k(x) for x in [0, width). kTaps: the number of taps
// as a constant, so that the sum unrolls, or 0 to take `taps`.
template <int kTaps>
void SumColumnsOf(const uint8_t* const* rows, const uint16_t* weights, int taps, int width,
                  uint16_t* sums) {
  const int n = kTaps > 0 ? kTaps : taps;
  forEachSpan(hn::ScalableTag<uint16_t>(), 0, width, [&](auto d, int x) {
    const hn::Rebind<uint8_t, decltype(d)> d8;
    auto sum = hn::Zero(d);
    for (int k = 0; k < n; ++k) {
      sum = sum + hn::Set(d, weights[k]) * hn::PromoteTo(d, hn::LoadU(d8, rows[k] + x));
    }
    hn::StoreU(sum, d, sums + x);
  });
}

// out(x) = (sum_k floor(t(x + k) w_k / 2^8) + 2^3) >> 4; `sums` starts
// `taps / 2` columns left of the image. kTaps as for SumColumnsOf.
template <int kTaps>
void SmoothRowOf(const uint16_t* sums, const uint16_t* weights, int taps, int width,
                 uint16_t* out) {
  const int n = kTaps > 0 ? kTaps : taps;
  forEachSpan(hn::ScalableTag<uint16_t>(), 0, width, [&](auto d, int x) {
    auto total = hn::Set(d, uint16_t{1 << 3});
    for (int k = 0; k < n; ++k) {
      total = total + hn::MulHigh(hn::LoadU(d, sums + x + k), hn::Set(d, weights[k] << 8));
    }
    hn::StoreU(hn::ShiftRight<4>(total), d, out + x);
  });
}

// The two passes with the tap counts of sigma <= 1 px as constants.
void SumColumns(const uint8_t* const* rows, const uint16_t* weights, int taps, int width,
                uint16_t* sums) {
  switch (taps) {
    case 3:
      return SumColumnsOf<3>(rows, weights, taps, width, sums);
    case 5:
      return SumColumnsOf<5>(rows, weights, taps, width, sums);
    default:
      return SumColumnsOf<0>(rows, weights, taps, width, sums);
  }
}

void SmoothRow(const uint16_t* sums, const uint16_t* weights, int taps, int width, uint16_t* out) {
  switch (taps) {
    case 3:
      return SmoothRowOf<3>(sums, weights, taps, width, out);
    case 5:
      return SmoothRowOf<5>(sums, weights, taps, width, out);
    default:
      return SmoothRowOf<0>(sums, weights, taps, width, out);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace lineloc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lineloc {
namespace {

constexpr int kWeightBits = 8;
constexpr int kWeightSum = 1 << kWeightBits;

}  // namespace

HWY_EXPORT(SumColumns);
HWY_EXPORT(SmoothRow);

GaussianSmoother::GaussianSmoother(double sigma_px) {
  if (!(sigma_px >= kMinSigmaPx)) {
    throw std::invalid_argument("Gaussian smoothing: sigma_px must be at least 0.5");
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
  rows_.resize(weights_.size());
}

void GaussianSmoother::smoothRow(const cv::Mat& grey, int y, uint16_t* out) {
  const int width = grey.cols;
  const int height = grey.rows;
  const int taps = static_cast<int>(weights_.size());
  column_sums_.resize(static_cast<size_t>(width) + 2 * radius_);
  uint16_t* sums = column_sums_.data() + radius_;
  for (int k = -radius_; k <= radius_; ++k) {
    rows_[k + radius_] = grey.ptr<uint8_t>(std::clamp(y + k, 0, height - 1));
  }
  HWY_DYNAMIC_DISPATCH(SumColumns)(rows_.data(), weights_.data(), taps, width, sums);
  std::fill(column_sums_.begin(), column_sums_.begin() + radius_, sums[0]);
  std::fill(column_sums_.end() - radius_, column_sums_.end(), sums[width - 1]);
  HWY_DYNAMIC_DISPATCH(SmoothRow)(column_sums_.data(), weights_.data(), taps, width, out);
}

std::vector<double> GaussianSmoother::kernel() const {
  std::vector<double> kernel(weights_.size());
  std::transform(weights_.begin(), weights_.end(), kernel.begin(),
                 [](uint16_t w) { return w / 256.0; });
  return kernel;
}

}  // namespace lineloc
#endif  // HWY_ONCE
