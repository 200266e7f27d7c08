#include "robot/vision/edges/edge_detector.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

// foreach_target.h compiles this file once per instruction set; it must
// come before highway.h.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "robot/vision/edges/edge_detector.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>
// clang-format on

#include "robot/vision/simd/for_each_span-inl.h"

HWY_BEFORE_NAMESPACE();
namespace lineloc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Sobel gx, gy and gx^2 + gy^2 of row `row` (between `above` and `below`)
// for x in [1, width - 1).
void GradientRow(const uint16_t* above, const uint16_t* row, const uint16_t* below, int width,
                 int16_t* gradient_x, int16_t* gradient_y, int32_t* squared_magnitude) {
  forEachSpan(hn::ScalableTag<int32_t>(), 1, width - 1, [&](auto d, int x) {
    const hn::Rebind<uint16_t, decltype(d)> d8;
    const hn::Rebind<int16_t, decltype(d)> d16;
    const auto at = [&](const uint16_t* p) { return hn::PromoteTo(d, hn::LoadU(d8, p)); };
    const auto top = at(above + x - 1) + at(above + x) + at(above + x) + at(above + x + 1);
    const auto bottom = at(below + x - 1) + at(below + x) + at(below + x) + at(below + x + 1);
    const auto right = at(above + x + 1) + at(row + x + 1) + at(row + x + 1) + at(below + x + 1);
    const auto left = at(above + x - 1) + at(row + x - 1) + at(row + x - 1) + at(below + x - 1);
    const auto gx = right - left;
    const auto gy = bottom - top;
    hn::StoreU(hn::DemoteTo(d16, gx), d16, gradient_x + x);
    hn::StoreU(hn::DemoteTo(d16, gy), d16, gradient_y + x);
    hn::StoreU(gx * gx + gy * gy, d, squared_magnitude + x);
  });
}

// Non-maximum suppression of row `mid` (between `up` and `down`) for x in
// [begin, end): the surviving columns, their |g|^2 and their neighbours' |g|^2
// behind and ahead along d and d go to `maxima`. d is (1, 0), (0, 1), (1, 1) or (1, -1) by the
// gradient's octant, negated when it points against the gradient. Returns the
// number of survivors.
int SuppressRow(const int32_t* up, const int32_t* mid, const int32_t* down,
                const int16_t* gradient_x, const int16_t* gradient_y, int begin, int end,
                int32_t min_squared_magnitude, EdgeRowMaxima& maxima) {
  size_t count = 0;
  forEachSpan(hn::ScalableTag<int32_t>(), begin, end, [&](auto d, int x) {
    const auto m = hn::LoadU(d, mid + x);
    const auto strong = hn::Not(m < hn::Set(d, min_squared_magnitude));
    if (hn::AllFalse(d, strong)) {
      return;
    }
    const hn::Rebind<int16_t, decltype(d)> d16;
    const auto gx = hn::PromoteTo(d, hn::LoadU(d16, gradient_x + x));
    const auto gy = hn::PromoteTo(d, hn::LoadU(d16, gradient_y + x));
    const auto ax = hn::Abs(gx);
    const auto ay = hn::Abs(gy);
    const auto two = hn::Set(d, 2);
    const auto five = hn::Set(d, 5);
    // |gy| <= tan(22.5 deg) |gx| (2/5 ~ 0.414): horizontal, and vice versa.
    const auto horizontal = hn::Not(ax * two < ay * five);
    const auto vertical = hn::AndNot(horizontal, hn::Not(ay * two < ax * five));
    const auto zero = hn::Zero(d);
    const auto one = hn::Set(d, 1);
    const auto same_signs = hn::Not((gx ^ gy) < zero);
    const auto dx = hn::IfThenElse(vertical, zero, one);
    const auto dy = hn::IfThenElse(
        horizontal, zero,
        hn::IfThenElse(vertical, one, hn::IfThenElse(same_signs, one, hn::Neg(one))));
    // Neighbours at p - d and p + d before the flip.
    const auto diagonal_back =
        hn::IfThenElse(same_signs, hn::LoadU(d, up + x - 1), hn::LoadU(d, down + x - 1));
    const auto diagonal_ahead =
        hn::IfThenElse(same_signs, hn::LoadU(d, down + x + 1), hn::LoadU(d, up + x + 1));
    const auto back = hn::IfThenElse(horizontal, hn::LoadU(d, mid + x - 1),
                                     hn::IfThenElse(vertical, hn::LoadU(d, up + x), diagonal_back));
    const auto ahead =
        hn::IfThenElse(horizontal, hn::LoadU(d, mid + x + 1),
                       hn::IfThenElse(vertical, hn::LoadU(d, down + x), diagonal_ahead));
    const auto flip = dx * gx + dy * gy < zero;
    const auto m_before = hn::IfThenElse(flip, ahead, back);
    const auto m_after = hn::IfThenElse(flip, back, ahead);
    const auto maximum = hn::And(strong, hn::AndNot(m<m_after, m> m_before));
    if (hn::AllFalse(d, maximum)) {
      return;
    }
    const auto keep = [&](decltype(m) v, std::vector<int32_t>& out) {
      return hn::CompressBlendedStore(v, maximum, d, out.data() + count);
    };
    keep(hn::Iota(d, x), maxima.x);
    keep(m, maxima.here);
    keep(m_before, maxima.before);
    keep(m_after, maxima.after);
    keep(hn::IfThenElse(flip, hn::Neg(dx), dx), maxima.direction_x);
    count += keep(hn::IfThenElse(flip, hn::Neg(dy), dy), maxima.direction_y);
  });
  return static_cast<int>(count);
}

// For each survivor: the offset along d of the Gaussian peak through the
// three |g|^2, delta = (l- - l+) / (2 (l- - 2 l0 + l+)) with l = log2 |g|^2,
// in [-1/2, 1/2] (0 where the three do not bend down), and 1 / |g|.
void SubPixelRow(EdgeRowMaxima& maxima) {
  forEachSpan(hn::ScalableTag<float>(), 0, maxima.count, [&](auto d, int i) {
    const hn::Rebind<int32_t, decltype(d)> di;
    const auto log2_of = [&](const std::vector<int32_t>& m) {
      return hn::Log2(d, hn::ConvertTo(d, hn::Max(hn::LoadU(di, m.data() + i), hn::Set(di, 1))));
    };
    const auto l_before = log2_of(maxima.before);
    const auto l_here = log2_of(maxima.here);
    const auto l_after = log2_of(maxima.after);
    const auto curvature = l_before - l_here - l_here + l_after;
    const auto half = hn::Set(d, 0.5f);
    const auto delta = hn::Set(d, 0.5f) * (l_before - l_after) / curvature;
    const auto bends = curvature < hn::Zero(d);
    hn::StoreU(hn::IfThenElseZero(bends, hn::Clamp(delta, hn::Neg(half), half)), d,
               maxima.offset.data() + i);
    const auto magnitude = hn::Sqrt(hn::ConvertTo(d, hn::LoadU(di, maxima.here.data() + i)));
    hn::StoreU(hn::Set(d, 1.0f) / magnitude, d, maxima.inverse_magnitude.data() + i);
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace lineloc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lineloc {
namespace {

constexpr float kSmoothedGain = GaussianSmoother::kOutputGain;
// Room for the step samples 3 px either side.
constexpr int kStepSampleDistancePx = 3;
constexpr int kBorderPx = kStepSampleDistancePx;
constexpr int kRingRows = 3;

}  // namespace

HWY_EXPORT(GradientRow);
HWY_EXPORT(SuppressRow);
HWY_EXPORT(SubPixelRow);

EdgeDetector::EdgeDetector(const EdgeDetectorOptions& options) : options_(options) {
  if (!(options.smoothing_sigma_px >= 0.0) || !(options.min_gradient > 0.0f) ||
      !(options.min_gradient <= 255.0f)) {
    throw std::invalid_argument(
        "edge detector: smoothing_sigma_px must be >= 0 and min_gradient in (0, 255]");
  }
  if (options.smoothing_sigma_px > 0.0) {
    smoother_.emplace(options.smoothing_sigma_px);
  }
  const double min_sobel = options.min_gradient * EdgeDetector::kGradientGain;
  min_squared_sobel_ = static_cast<int32_t>(std::ceil(min_sobel * min_sobel));
}

void EdgeDetector::prepareBuffers(cv::Size size) {
  points_.clear();
  for (cv::Mat* gradient : {&gradient_x_, &gradient_y_}) {
    gradient->create(size, CV_16S);
    std::fill_n(gradient->ptr<int16_t>(0), size.width, 0);
    std::fill_n(gradient->ptr<int16_t>(size.height - 1), size.width, 0);
  }
  squared_magnitude_rows_.assign(static_cast<size_t>(kRingRows) * size.width, 0);
  point_index_rows_.assign(static_cast<size_t>(kRingRows) * size.width, -1);
  first_point_of_row_.assign(size.height + 1, 0);
  const size_t room = size.width;
  for (std::vector<int32_t>* column : {&maxima_.x, &maxima_.here, &maxima_.before, &maxima_.after,
                                       &maxima_.direction_x, &maxima_.direction_y}) {
    column->resize(room);
  }
  maxima_.offset.resize(room);
  maxima_.inverse_magnitude.resize(room);
}

int32_t* EdgeDetector::squaredMagnitudeRow(int y) {
  return squared_magnitude_rows_.data() + static_cast<size_t>(y % kRingRows) * smoothed_.cols;
}

int32_t* EdgeDetector::pointIndexRow(int y) {
  return point_index_rows_.data() + static_cast<size_t>(y % kRingRows) * smoothed_.cols;
}

void EdgeDetector::detect(const cv::Mat& grey, GradientRowListener* listener) {
  if (smoother_) {
    smoother_->smooth(grey, smoothed_);
  } else {
    grey.convertTo(smoothed_, CV_16U, kSmoothedGain);
  }
  const int width = grey.cols;
  const int height = grey.rows;
  prepareBuffers(grey.size());
  const auto tell = [&](int y) {
    if (listener != nullptr) {
      listener->gradientRow(y, gradient_x_, gradient_y_);
    }
  };
  tell(0);
  const int first_row = kBorderPx;
  const int last_row = height - kBorderPx - 1;
  for (int y = 1; y < height - 1; ++y) {
    int16_t* gx = gradient_x_.ptr<int16_t>(y);
    int16_t* gy = gradient_y_.ptr<int16_t>(y);
    HWY_DYNAMIC_DISPATCH(GradientRow)
    (smoothed_.ptr<uint16_t>(y - 1), smoothed_.ptr<uint16_t>(y), smoothed_.ptr<uint16_t>(y + 1),
     width, gx, gy, squaredMagnitudeRow(y));
    gx[0] = gx[width - 1] = gy[0] = gy[width - 1] = 0;
    tell(y);
    const int row = y - 1;
    if (row < first_row || row > last_row + 1) {
      continue;
    }
    startRow(row);
    if (row <= last_row) {
      addPoints(row);
    }
    if (row > first_row) {
      findNeighbours(row - 1);
    }
  }
  tell(height - 1);
}

// Row y takes the index ring's slot from row y - 3.
void EdgeDetector::startRow(int y) {
  int32_t* index = pointIndexRow(y);
  if (y - kRingRows >= 0) {
    for (int32_t i = first_point_of_row_[y - kRingRows]; i < first_point_of_row_[y - 2]; ++i) {
      index[points_[i].pixel_x] = -1;
    }
  }
  first_point_of_row_[y] = static_cast<int32_t>(points_.size());
  first_point_of_row_[y + 1] = first_point_of_row_[y];
}

void EdgeDetector::addPoints(int y) {
  maxima_.count = HWY_DYNAMIC_DISPATCH(SuppressRow)(
      squaredMagnitudeRow(y - 1), squaredMagnitudeRow(y), squaredMagnitudeRow(y + 1),
      gradient_x_.ptr<int16_t>(y), gradient_y_.ptr<int16_t>(y), kBorderPx,
      smoothed_.cols - kBorderPx, min_squared_sobel_, maxima_);
  HWY_DYNAMIC_DISPATCH(SubPixelRow)(maxima_);
  const int16_t* gx = gradient_x_.ptr<int16_t>(y);
  const int16_t* gy = gradient_y_.ptr<int16_t>(y);
  int32_t* index = pointIndexRow(y);
  const int smoothed_stride = static_cast<int>(smoothed_.step1());
  const uint16_t* grey = smoothed_.ptr<uint16_t>(y);
  for (int i = 0; i < maxima_.count; ++i) {
    const int x = maxima_.x[i];
    const int dx = maxima_.direction_x[i];
    const int dy = maxima_.direction_y[i];
    const float delta = maxima_.offset[i];
    const int step_offset = kStepSampleDistancePx * (dy * smoothed_stride + dx);
    const Eigen::Vector2f sobel(gx[x], gy[x]);
    EdgePoint point;
    point.position = {static_cast<float>(x) + delta * static_cast<float>(dx),
                      static_cast<float>(y) + delta * static_cast<float>(dy)};
    point.gradient = sobel / EdgeDetector::kGradientGain;
    point.normal = sobel * maxima_.inverse_magnitude[i];
    point.step =
        (static_cast<float>(grey[x + step_offset]) - grey[x - step_offset]) / kSmoothedGain;
    point.pixel_x = x;
    point.pixel_y = y;
    index[x] = static_cast<int32_t>(points_.size());
    points_.push_back(point);
  }
  first_point_of_row_[y + 1] = static_cast<int32_t>(points_.size());
}

// The nearest same-polarity 8-neighbours ahead and behind of row y's points,
// while rows y - 1 .. y + 1 are in the index ring.
void EdgeDetector::findNeighbours(int y) {
  const int32_t* rows[3] = {pointIndexRow(y - 1), pointIndexRow(y), pointIndexRow(y + 1)};
  for (int32_t p = first_point_of_row_[y]; p < first_point_of_row_[y + 1]; ++p) {
    EdgePoint& here = points_[p];
    const Eigen::Vector2f tangent(-here.normal.y(), here.normal.x());
    float ahead_distance = std::numeric_limits<float>::max();
    float behind_distance = ahead_distance;
    for (const int32_t* row : rows) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int32_t candidate = row[here.pixel_x + dx];
        if (candidate < 0 || candidate == p || points_[candidate].normal.dot(here.normal) <= 0.0f) {
          continue;
        }
        const Eigen::Vector2f offset = points_[candidate].position - here.position;
        const float distance = offset.squaredNorm();
        const bool ahead = offset.dot(tangent) > 0.0f;
        float& nearest = ahead ? ahead_distance : behind_distance;
        if (distance < nearest) {
          nearest = distance;
          (ahead ? here.ahead : here.behind) = candidate;
        }
      }
    }
  }
}

}  // namespace lineloc
#endif  // HWY_ONCE
