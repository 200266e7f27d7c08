#include "backbone/matching/oriented_distance_map.h"

#include <algorithm>
#include <cmath>

namespace lineloc {
namespace {

constexpr int kBins = OrientedDistanceMap::kOrientationBins;
constexpr double kBinWidthRad = M_PI / kBins;

// Position of a direction in bin units, in [0, bins).
double binCoordinate(double direction_rad) {
  const double coordinate = std::fmod(direction_rad / kBinWidthRad, kBins);
  return coordinate < 0.0 ? coordinate + kBins : coordinate;
}

int wrapBin(int bin) {
  return (bin % kBins + kBins) % kBins;
}

}  // namespace

int OrientedDistanceMap::binOf(double direction_rad) {
  return wrapBin(static_cast<int>(std::lround(binCoordinate(direction_rad))));
}

OrientedDistanceMap::OrientedDistanceMap(const std::vector<ImageSegment>& segments, int width_px,
                                         int height_px, const DistanceMapOptions& options)
    : truncation_px_(static_cast<float>(options.truncation_px)),
      level_px_(truncation_px_ / kTruncationLevel),
      downsample_(std::max(1, options.downsample)) {
  const cv::Size size((width_px + downsample_ - 1) / downsample_,
                      (height_px + downsample_ - 1) / downsample_);
  for (cv::Mat1b& map : maps_) {
    map = cv::Mat1b(size, static_cast<uchar>(kTruncationLevel));
  }
  for (const ImageSegment& segment : segments) {
    const Eigen::Vector2d a = segment.start.cast<double>();
    const Eigen::Vector2d b = segment.end.cast<double>();
    const Eigen::Vector2d along = b - a;
    if (!(along.norm() >= options.min_segment_length_px)) {
      continue;
    }
    const double coordinate = binCoordinate(std::atan2(along.y(), along.x()));
    const int nearest = static_cast<int>(std::lround(coordinate));
    const int neighbour = coordinate > nearest ? nearest + 1 : nearest - 1;
    for (const int bin : {wrapBin(nearest), wrapBin(neighbour)}) {
      drawDistanceBand(maps_[bin], a, b);
    }
  }
}

// Row y of the band meets the capsule {q : |q - s| <= tau} inside
// [min x - tau, max x + tau] and, for a segment that is not horizontal, inside
// the strip |n . (q - a)| <= tau about its line: x = x_line(y) +- tau / |n_x|.
// Each row's cells are filled kLanes at a time, in single precision relative
// to a: |q - a| stays below the image's size, so the distance is exact to
// 1e-4 px, a hundredth of a level.
void OrientedDistanceMap::drawDistanceBand(cv::Mat1b& map, const Eigen::Vector2d& a,
                                           const Eigen::Vector2d& b) const {
  constexpr int kLanes = 8;
  using Lanes = Eigen::Array<float, kLanes, 1>;
  const double scale = downsample_;
  const double tau = truncation_px_;
  const Eigen::Vector2d along = b - a;
  const double abs_normal_x = std::abs(along.y()) / along.norm();
  const int row_first =
      std::max(0, static_cast<int>(std::ceil((std::min(a.y(), b.y()) - tau) / scale)));
  const int row_last =
      std::min(map.rows - 1, static_cast<int>(std::floor((std::max(a.y(), b.y()) + tau) / scale)));
  const double x_min = std::min(a.x(), b.x()) - tau;
  const double x_max = std::max(a.x(), b.x()) + tau;
  const float along_x = static_cast<float>(along.x());
  const float along_y = static_cast<float>(along.y());
  const float inverse_length_squared = static_cast<float>(1.0 / along.squaredNorm());
  const float levels_per_px = 1.0f / level_px_;
  const Lanes lane_x = Lanes::LinSpaced(kLanes, 0.0f, static_cast<float>((kLanes - 1) * scale));
  for (int row = row_first; row <= row_last; ++row) {
    const double y = row * scale;
    double from = x_min;
    double to = x_max;
    if (abs_normal_x > 1e-9) {
      const double x_line = a.x() + along.x() * (y - a.y()) / along.y();
      from = std::max(from, x_line - tau / abs_normal_x);
      to = std::min(to, x_line + tau / abs_normal_x);
    }
    const int col_first = std::max(0, static_cast<int>(std::ceil(from / scale)));
    const int col_last = std::min(map.cols - 1, static_cast<int>(std::floor(to / scale)));
    const float offset_y = static_cast<float>(y - a.y());
    uchar* cells = map[row];
    for (int col = col_first; col <= col_last; col += kLanes) {
      const Lanes offset_x = static_cast<float>(col * scale - a.x()) + lane_x;
      const Lanes t =
          ((offset_x * along_x + offset_y * along_y) * inverse_length_squared).max(0.0f).min(1.0f);
      const Lanes distance =
          ((offset_x - t * along_x).square() + (offset_y - t * along_y).square()).sqrt();
      const Eigen::Array<int, kLanes, 1> level =
          (distance * levels_per_px + 0.5f).min(static_cast<float>(kTruncationLevel)).cast<int>();
      for (int lane = 0; lane < std::min(kLanes, col_last - col + 1); ++lane) {
        cells[col + lane] = std::min(cells[col + lane], static_cast<uchar>(level[lane]));
      }
    }
  }
}

int OrientedDistanceMap::lookup(const cv::Mat1b& map, const Eigen::Vector2d& scaled_pixel) const {
  const double u = scaled_pixel.x() + 0.5;
  const double v = scaled_pixel.y() + 0.5;
  // Written so that NaN fails the test too.
  if (!(u >= 0.0 && v >= 0.0 && u < map.cols && v < map.rows)) {
    return kTruncationLevel;
  }
  return map(static_cast<int>(v), static_cast<int>(u));
}

float OrientedDistanceMap::distance(const Eigen::Vector2d& pixel, double direction_rad) const {
  const int level = lookup(maps_[binOf(direction_rad)], pixel / downsample_);
  return level == kTruncationLevel ? truncation_px_ : level * level_px_;
}

double OrientedDistanceMap::coveredLength(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                          double spacing_px) const {
  const Eigen::Vector2d along = b - a;
  const double length = along.norm();
  const int samples = static_cast<int>(length / spacing_px);
  if (samples == 0) {
    return 0.0;
  }
  const cv::Mat1b& map = maps_[binOf(std::atan2(along.y(), along.x()))];
  const Eigen::Vector2d step = along / (static_cast<double>(samples) * downsample_);
  Eigen::Vector2d sample = a / downsample_ + 0.5 * step;
  int level_sum = 0;
  for (int k = 0; k < samples; ++k, sample += step) {
    level_sum += lookup(map, sample);
  }
  return length * (1.0 - static_cast<double>(level_sum) / (samples * kTruncationLevel));
}

}  // namespace lineloc
