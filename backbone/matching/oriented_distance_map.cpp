#include "backbone/matching/oriented_distance_map.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace lineloc {
namespace {

constexpr int kBins = OrientedDistanceMap::kOrientationBins;
constexpr double kBinWidthRad = M_PI / kBins;
constexpr uchar kBackground = 255;

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
      downsample_(std::max(1, options.downsample)) {
  const cv::Size size((width_px + downsample_ - 1) / downsample_,
                      (height_px + downsample_ - 1) / downsample_);
  std::array<cv::Mat1b, kBins> masks;
  for (cv::Mat1b& mask : masks) {
    mask = cv::Mat1b(size, kBackground);
  }
  const double scale = 1.0 / downsample_;
  for (const ImageSegment& segment : segments) {
    const Eigen::Vector2f along = segment.end - segment.start;
    if (along.norm() < options.min_segment_length_px) {
      continue;
    }
    const double coordinate = binCoordinate(std::atan2(along.y(), along.x()));
    const int nearest = static_cast<int>(std::lround(coordinate));
    const int neighbour = coordinate > nearest ? nearest + 1 : nearest - 1;
    const cv::Point2d a(segment.start.x() * scale, segment.start.y() * scale);
    const cv::Point2d b(segment.end.x() * scale, segment.end.y() * scale);
    for (const int bin : {wrapBin(nearest), wrapBin(neighbour)}) {
      cv::line(masks[bin], a, b, cv::Scalar(0), 1, cv::LINE_8);
    }
  }
  for (int bin = 0; bin < kBins; ++bin) {
    cv::distanceTransform(masks[bin], maps_[bin], cv::DIST_L2, cv::DIST_MASK_5, CV_32F);
    maps_[bin] = cv::min(maps_[bin] * downsample_, truncation_px_);
  }
}

float OrientedDistanceMap::distance(const Eigen::Vector2d& pixel, double direction_rad) const {
  const cv::Mat1f& map = maps_[binOf(direction_rad)];
  const double u = pixel.x() / downsample_;
  const double v = pixel.y() / downsample_;
  // Written so that NaN fails the test too.
  if (!(u >= 0.0 && v >= 0.0 && u < map.cols && v < map.rows)) {
    return truncation_px_;
  }
  return map(static_cast<int>(v), static_cast<int>(u));
}

}  // namespace lineloc
