#include "robot/vision/edges/edge_detector.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
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

#include "robot/vision/simd/append_selected-inl.h"
#include "robot/vision/simd/for_each_span-inl.h"

HWY_BEFORE_NAMESPACE();
namespace lineloc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Sobel gx, gy and gx^2 + gy^2 of row `row` (between `above` and `below`,
// values <= 2^12) for x in [1, width - 1): the Sobel sums fit 16 bits.
void GradientRow(const uint16_t* above, const uint16_t* row, const uint16_t* below, int width,
                 int16_t* gradient_x, int16_t* gradient_y, int32_t* squared_magnitude) {
  forEachSpan(hn::ScalableTag<int16_t>(), 1, width - 1, [&](auto d, int x) {
    const hn::Rebind<uint16_t, decltype(d)> du;
    const auto at = [&](const uint16_t* p) { return hn::BitCast(d, hn::LoadU(du, p)); };
    const auto down = at(below + x) - at(above + x);
    const auto down_left = at(below + x - 1) - at(above + x - 1);
    const auto down_right = at(below + x + 1) - at(above + x + 1);
    const auto right = at(row + x + 1) - at(row + x - 1);
    const auto right_above = at(above + x + 1) - at(above + x - 1);
    const auto right_below = at(below + x + 1) - at(below + x - 1);
    hn::StoreU(right_above + right + right + right_below, d, gradient_x + x);
    hn::StoreU(down_left + down + down + down_right, d, gradient_y + x);
  });
  forEachSpan(hn::ScalableTag<int32_t>(), 1, width - 1, [&](auto d, int x) {
    const hn::Rebind<int16_t, decltype(d)> d16;
    const auto gx = hn::PromoteTo(d, hn::LoadU(d16, gradient_x + x));
    const auto gy = hn::PromoteTo(d, hn::LoadU(d16, gradient_y + x));
    hn::StoreU(gx * gx + gy * gy, d, squared_magnitude + x);
  });
}

// Non-maximum suppression of row `mid` (between `up` and `down`) for x in
// [begin, end): the surviving columns, their |g|^2 and their neighbours' |g|^2
// behind and ahead along d and d go to `maxima`. d is (1, 0), (0, 1), (1, 1) or (1, -1) by the
// gradient's octant, negated when it points against the gradient. Returns the
// number of survivors.
int SuppressRow(const int32_t* up, const int32_t* mid, const int32_t* down,
                const int16_t* gradient_x, const int16_t* gradient_y, const int32_t* columns,
                int begin, int end, int32_t min_squared_magnitude, EdgeRowMaxima& maxima) {
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
      return appendSelected(d, v, maximum, out.data() + count);
    };
    keep(hn::LoadU(d, columns + x), maxima.x);
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
    const auto magnitude_of = [&](const std::vector<int32_t>& m) {
      return hn::ConvertTo(d, hn::Max(hn::LoadU(di, m.data() + i), hn::Set(di, 1)));
    };
    // l- - l0 and l+ - l0 as logs of ratios: two logarithms instead of three.
    const auto here = magnitude_of(maxima.here);
    const auto below_before = hn::Log2(d, magnitude_of(maxima.before) / here);
    const auto below_after = hn::Log2(d, magnitude_of(maxima.after) / here);
    const auto curvature = below_before + below_after;
    const auto half = hn::Set(d, 0.5f);
    const auto delta = half * (below_before - below_after) / curvature;
    const auto bends = curvature < hn::Zero(d);
    hn::StoreU(hn::IfThenElseZero(bends, hn::Clamp(delta, hn::Neg(half), half)), d,
               maxima.offset.data() + i);
    hn::StoreU(hn::Set(d, 1.0f) / hn::Sqrt(here), d, maxima.inverse_magnitude.data() + i);
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace lineloc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lineloc {
namespace {

constexpr int kSmoothedGain = GaussianSmoother::kOutputGain;
// Room for the step samples 3 px either side.
constexpr int kStepSampleDistancePx = 3;
constexpr int kBorderPx = kStepSampleDistancePx;
constexpr int kRingRows = 3;

std::vector<double> convolve(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> ab(a.size() + b.size() - 1, 0.0);
  for (size_t i = 0; i < a.size(); ++i) {
    for (size_t j = 0; j < b.size(); ++j) {
      ab[i + j] += a[i] * b[j];
    }
  }
  return ab;
}

double sumOfSquares(const std::vector<double>& a) {
  return std::inner_product(a.begin(), a.end(), a.begin(), 0.0);
}

// EdgeNoise for sigma = 1 and the smoothing kernel w (edge_detector.h).
EdgeNoise unitNoise(const std::vector<double>& w) {
  const double smoothed_variance = sumOfSquares(w);
  const auto lag = static_cast<size_t>(2 * kStepSampleDistancePx);
  const std::vector<double> autocorrelation = convolve(w, w);  // centre at w.size() - 1
  const size_t centre = w.size() - 1;
  const double rho_step = centre + lag < autocorrelation.size()
                              ? autocorrelation[centre + lag] / autocorrelation[centre]
                              : 0.0;
  EdgeNoise noise;
  noise.image_sigma = 1.0;
  noise.gradient_sigma = std::sqrt(sumOfSquares(convolve(w, {0.25, 0.5, 0.25})) *
                                   sumOfSquares(convolve(w, {-0.5, 0.0, 0.5})));
  noise.step_sigma = smoothed_variance * std::sqrt(2.0 * (1.0 - rho_step));
  noise.correlation_length_px = 1.0 / smoothed_variance;
  return noise;
}

}  // namespace

HWY_EXPORT(GradientRow);
HWY_EXPORT(SuppressRow);
HWY_EXPORT(SubPixelRow);

EdgeDetector::EdgeDetector(const EdgeDetectorOptions& options) : options_(options) {
  if (!(options.smoothing_sigma_px == 0.0 ||
        options.smoothing_sigma_px >= GaussianSmoother::kMinSigmaPx) ||
      !(options.min_gradient > 0.0f) || !(options.min_gradient <= 255.0f) ||
      !(options.max_link_turn_rad > 0.0 && options.max_link_turn_rad < M_PI_2)) {
    throw std::invalid_argument(
        "edge detector: smoothing_sigma_px must be 0 or >= 0.5, min_gradient in (0, 255], "
        "max_link_turn_rad in (0, pi/2)");
  }
  if (options.smoothing_sigma_px > 0.0) {
    smoother_.emplace(options.smoothing_sigma_px);
  }
  unit_noise_ = unitNoise(smoother_ ? smoother_->kernel() : std::vector<double>{1.0});
  cos_max_turn_ = static_cast<float>(std::cos(options.max_link_turn_rad));
}

EdgeNoise EdgeDetector::noise(double image_sigma) const {
  EdgeNoise noise = unit_noise_;
  noise.image_sigma = image_sigma;
  noise.gradient_sigma *= image_sigma;
  noise.step_sigma *= image_sigma;
  return noise;
}

void EdgeDetector::prepareBuffers(cv::Size size) {
  points_.clear();
  smoothed_.create(size, CV_16U);
  for (cv::Mat* gradient : {&gradient_x_, &gradient_y_}) {
    gradient->create(size, CV_16S);
    std::fill_n(gradient->ptr<int16_t>(0), size.width, 0);
    std::fill_n(gradient->ptr<int16_t>(size.height - 1), size.width, 0);
  }
  squared_magnitude_rows_.assign(static_cast<size_t>(kRingRows) * size.width, 0);
  point_index_rows_.assign(static_cast<size_t>(kRingRows) * size.width, -1);
  no_points_.assign(size.width, -1);
  occupancy_rows_.assign(static_cast<size_t>(kRingRows) * (size.width / 8 + 2), 0);
  normal_rows_.assign(static_cast<size_t>(kRingRows) * size.width, Eigen::Vector2f::Zero());
  first_point_of_row_.assign(size.height + 1, 0);
  for (std::vector<int32_t>* per_point : {&nearest_ahead_, &nearest_behind_, &next_, &previous_}) {
    per_point->clear();
  }
  column_numbers_.resize(size.width);
  std::iota(column_numbers_.begin(), column_numbers_.end(), 0);
  const size_t room = static_cast<size_t>(size.width) + kCompressSlack;
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

int EdgeDetector::occupancyRowBytes() const {
  return smoothed_.cols / 8 + 2;
}

uint8_t* EdgeDetector::occupancyRow(int y) {
  return occupancy_rows_.data() + static_cast<size_t>(y % kRingRows) * occupancyRowBytes();
}

Eigen::Vector2f* EdgeDetector::normalRow(int y) {
  return normal_rows_.data() + static_cast<size_t>(y % kRingRows) * smoothed_.cols;
}

void EdgeDetector::detect(const cv::Mat& grey, double noise_sigma, GradientRowListener* listener) {
  const int width = grey.cols;
  const int height = grey.rows;
  const double noise_gradient = noise(noise_sigma).gradient_sigma *
                                std::sqrt(2.0 * std::log(static_cast<double>(width) * height));
  const double min_sobel =
      std::max<double>(options_.min_gradient, noise_gradient) * EdgeDetector::kGradientGain;
  min_squared_sobel_ = static_cast<int32_t>(std::min(
      std::ceil(min_sobel * min_sobel), static_cast<double>(std::numeric_limits<int32_t>::max())));
  prepareBuffers(grey.size());
  const auto tell = [&](int y) {
    if (listener != nullptr) {
      listener->gradientRow(y, gradient_x_, gradient_y_);
    }
  };
  // Smoothed rows are made as the rows 3 px below need them (step samples).
  int smoothed_rows = 0;
  const auto smooth_through = [&](int last) {
    for (; smoothed_rows <= std::min(last, height - 1); ++smoothed_rows) {
      smoothRow(grey, smoothed_rows);
    }
  };
  tell(0);
  const int first_row = kBorderPx;
  const int last_row = height - kBorderPx - 1;
  for (int y = 1; y < height - 1; ++y) {
    smooth_through(y + kStepSampleDistancePx - 1);
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

void EdgeDetector::smoothRow(const cv::Mat& grey, int y) {
  uint16_t* out = smoothed_.ptr<uint16_t>(y);
  if (smoother_) {
    smoother_->smoothRow(grey, y, out);
    return;
  }
  const uint8_t* in = grey.ptr<uint8_t>(y);
  std::transform(in, in + grey.cols, out,
                 [](uint8_t value) { return static_cast<uint16_t>(value * kSmoothedGain); });
}

// Row y takes the index ring's slot from row y - 3.
void EdgeDetector::startRow(int y) {
  int32_t* index = pointIndexRow(y);
  std::fill_n(occupancyRow(y), occupancyRowBytes(), 0);
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
      gradient_x_.ptr<int16_t>(y), gradient_y_.ptr<int16_t>(y), column_numbers_.data(), kBorderPx,
      smoothed_.cols - kBorderPx, min_squared_sobel_, maxima_);
  HWY_DYNAMIC_DISPATCH(SubPixelRow)(maxima_);
  const int16_t* gx = gradient_x_.ptr<int16_t>(y);
  const int16_t* gy = gradient_y_.ptr<int16_t>(y);
  int32_t* index = pointIndexRow(y);
  uint8_t* occupied = occupancyRow(y);
  Eigen::Vector2f* normal = normalRow(y);
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
    point.gradient = sobel * (1.0f / EdgeDetector::kGradientGain);
    point.normal = sobel * maxima_.inverse_magnitude[i];
    point.step =
        static_cast<float>(grey[x + step_offset] - grey[x - step_offset]) * (1.0f / kSmoothedGain);
    point.pixel_x = x;
    point.pixel_y = y;
    index[x] = static_cast<int32_t>(points_.size());
    occupied[x >> 3] = static_cast<uint8_t>(occupied[x >> 3] | 1u << (x & 7));
    normal[x] = point.normal;
    points_.push_back(point);
  }
  for (std::vector<int32_t>* per_point : {&nearest_ahead_, &nearest_behind_, &next_, &previous_}) {
    per_point->resize(points_.size(), -1);
  }
  first_point_of_row_[y + 1] = static_cast<int32_t>(points_.size());
}

// The nearest 8-neighbours ahead and behind of row y's points whose gradient
// turns by at most max_link_turn,
// while rows y - 1 .. y + 1 are in the index ring; then the links of row y's
// points to points searched before them (rows above, earlier in the row)
// where the choice is mutual.
void EdgeDetector::findNeighbours(int y) {
  const int32_t first = first_point_of_row_[y];
  const int32_t end = first_point_of_row_[y + 1];
  // The index row of each neighbour step shifted by dx + 1, to be read at
  // x - 1; [kNone]: a row without points.
  const int32_t* at_step[NeighbourSteps::kNone + 1];
  // The normal row of each neighbour step shifted by dx, to be read at x.
  const Eigen::Vector2f* normal_at_step[8];
  for (int k = 0; k < 8; ++k) {
    const NeighbourStep& step = kNeighbourSteps[k];
    at_step[k] = pointIndexRow(y + step.dy) + step.dx + 1;
    normal_at_step[k] = normalRow(y + step.dy) + step.dx;
  }
  at_step[NeighbourSteps::kNone] = no_points_.data();
  const uint8_t* occupied_rows[3] = {occupancyRow(y - 1), occupancyRow(y), occupancyRow(y + 1)};
  for (int32_t p = first; p < end; ++p) {
    const EdgePoint& here = points_[p];
    const int x = here.pixel_x;
    // Bits x - 1 .. x + 1 of each row's occupancy, in kNeighbourSteps order.
    const int byte = (x - 1) >> 3;
    const int bit = (x - 1) & 7;
    const auto three = [&](const uint8_t* bits) {
      return ((bits[byte] | bits[byte + 1] << 8) >> bit) & 7u;
    };
    const unsigned middle = three(occupied_rows[1]);
    const unsigned occupied = three(occupied_rows[0]) | (middle & 1u) << 3 | (middle & 4u) << 2 |
                              three(occupied_rows[2]) << 5;
    // Only neighbours whose gradient turns by at most max_link_turn count:
    // all 8 tested without branches, the pixels without a point masked out.
    unsigned turns_little = 0;
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector2f& there = normal_at_step[k][x];
      turns_little |= static_cast<unsigned>(there.dot(here.normal) >= cos_max_turn_) << k;
    }
    const unsigned usable = turns_little & occupied;
    const NeighbourSteps::Choice choice =
        neighbour_steps_.choose(-here.normal.y(), here.normal.x(), usable);
    nearest_ahead_[p] = at_step[choice.ahead][x - 1];
    nearest_behind_[p] = at_step[choice.behind][x - 1];
  }
  // Links to points searched before: selects and a dummy target instead of
  // branches, whose outcome is as good as random.
  int32_t unlinked;
  for (int32_t p = first; p < end; ++p) {
    const int32_t behind = nearest_behind_[p];
    const bool from_behind =
        (behind >= 0) & (behind < p) & (nearest_ahead_[std::max(behind, 0)] == p);
    *(from_behind ? &next_[behind] : &unlinked) = p;
    previous_[p] = from_behind ? behind : previous_[p];
    const int32_t ahead = nearest_ahead_[p];
    const bool to_ahead = (ahead >= 0) & (ahead < p) & (nearest_behind_[std::max(ahead, 0)] == p);
    *(to_ahead ? &previous_[ahead] : &unlinked) = p;
    next_[p] = to_ahead ? ahead : next_[p];
  }
}

}  // namespace lineloc
#endif  // HWY_ONCE
