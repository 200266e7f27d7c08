#include "robot/vision/features/feature_extractor.h"

#include <fmt/format.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace lineloc {
namespace {

bool sideInRange(int side) {
  return side >= FeatureExtractor::kMinImageSidePx && side <= FeatureExtractor::kMaxImageSidePx;
}

const CameraCalibration& checkedSize(const CameraCalibration& calibration) {
  const PinholeCamera& camera = calibration.camera;
  if (!sideInRange(camera.width) || !sideInRange(camera.height)) {
    throw std::invalid_argument(
        fmt::format("feature extractor: calibration image size {}x{} is outside {}..{} px per side",
                    camera.width, camera.height, FeatureExtractor::kMinImageSidePx,
                    FeatureExtractor::kMaxImageSidePx));
  }
  return calibration;
}

}  // namespace

FeatureExtractorOptions trackingFrontEndOptions() {
  FeatureExtractorOptions options;
  options.edges.min_gradient = 4.0f;
  return options;
}

FeatureExtractor::FeatureExtractor(const CameraCalibration& calibration,
                                   const FeatureExtractorOptions& options)
    : calibration_(checkedSize(calibration)),
      options_(options),
      undistortion_(calibration),
      edge_detector_(options.edges),
      linker_(options.linking),
      line_extractor_(options.lines),
      corner_detector_(options.corners),
      corner_thread_([this] { detectCorners(); }) {
  if (!(options.junction_radius_px >= 0.0)) {
    throw std::invalid_argument("feature extractor: junction_radius_px must be >= 0");
  }
}

const cv::Mat& FeatureExtractor::toGrey(const cv::Mat& image) {
  const PinholeCamera& camera = calibration_.camera;
  if (image.empty()) {
    throw std::invalid_argument("feature extractor: the image is empty");
  }
  if (image.dims != 2 || image.depth() != CV_8U) {
    throw std::invalid_argument(fmt::format(
        "feature extractor: the image must be 8-bit 2D, got depth {} with {} dimensions",
        image.depth(), image.dims));
  }
  if (image.cols != camera.width || image.rows != camera.height) {
    throw std::invalid_argument(
        fmt::format("feature extractor: the image is {}x{}, the calibration is for {}x{}",
                    image.cols, image.rows, camera.width, camera.height));
  }
  switch (image.channels()) {
    case 1:
      return image;
    case 3:
      cv::cvtColor(image, grey_, cv::COLOR_BGR2GRAY);
      return grey_;
    case 4:
      cv::cvtColor(image, grey_, cv::COLOR_BGRA2GRAY);
      return grey_;
    default:
      throw std::invalid_argument(fmt::format(
          "feature extractor: the image has {} channels; 1, 3 or 4 expected", image.channels()));
  }
}

const FrameFeatures& FeatureExtractor::extract(const cv::Mat& image) {
  const cv::Mat& grey = toGrey(image);
  features_.corners.clear();
  features_.noise_sigma = noise_estimator_.estimate(grey);
  if (!options_.detect_corners) {
    edge_detector_.detect(grey, features_.noise_sigma);
    fitLines();
    return features_;
  }
  if (options_.corners_on_own_thread) {
    edge_detector_.detect(grey, features_.noise_sigma);
    corner_thread_.runAlongside([this] { fitLines(); });
  } else {
    corner_detector_.begin(grey.size(), EdgeDetector::kGradientGain);
    edge_detector_.detect(grey, features_.noise_sigma, this);
    fitLines();
    corner_detector_.finish(edge_detector_.gradientX(), edge_detector_.gradientY());
  }
  exportCorners();
  return features_;
}

void FeatureExtractor::gradientRow(int y, const cv::Mat& gradient_x, const cv::Mat& gradient_y) {
  corner_detector_.addRow(y, gradient_x, gradient_y);
}

void FeatureExtractor::detectCorners() {
  corner_detector_.detect(edge_detector_.gradientX(), edge_detector_.gradientY(),
                          EdgeDetector::kGradientGain);
}

void FeatureExtractor::fitLines() {
  linker_.link(edge_detector_.next(), edge_detector_.previous());
  line_extractor_.extract(edge_detector_.points(), linker_, undistortion_,
                          edge_detector_.gradientX().size(),
                          edge_detector_.noise(features_.noise_sigma));
  features_.rejected_segments = line_extractor_.rejectedSegments();
  exportSegments();
}

void FeatureExtractor::exportSegments() {
  features_.segments.clear();
  features_.segment_quality.clear();
  for (const LineSegment& line : line_extractor_.segments()) {
    ImageSegment segment;
    segment.start = line.start().cast<float>();
    segment.end = line.end().cast<float>();
    segment.start_covariance = line.startCovariance().cast<float>();
    segment.end_covariance = line.endCovariance().cast<float>();
    segment.contrast = static_cast<float>(line.contrast());
    segment.polarity = line.polarity();
    features_.segments.push_back(segment);
    features_.segment_quality.push_back({static_cast<float>(line.fit.sigma_offset_px),
                                         static_cast<float>(line.fit.sigma_angle_rad),
                                         static_cast<int>(line.moments.n)});
  }
}

void FeatureExtractor::exportCorners() {
  junctions_by_x_.assign(line_extractor_.junctions().begin(), line_extractor_.junctions().end());
  std::sort(junctions_by_x_.begin(), junctions_by_x_.end(),
            [](const Junction& a, const Junction& b) { return a.position.x() < b.position.x(); });
  for (const ForstnerCorner& found : corner_detector_.corners()) {
    const Eigen::Matrix2f J = undistortion_.jacobian(found.position);
    ImageCorner corner;
    corner.position = undistortion_.undistort(found.position);
    if (!corner.position.allFinite() || !J.allFinite()) {
      continue;  // a fisheye's corner outside the undistorted view
    }
    // J C J^T, symmetric as a covariance is (float products round apart).
    const Eigen::Matrix2f covariance = J * found.covariance * J.transpose();
    corner.covariance = 0.5f * (covariance + covariance.transpose());
    corner.strength = found.weight;
    if (const Junction* junction = nearestJunction(corner.position)) {
      corner.position = junction->position.cast<float>();
      corner.covariance = junction->covariance.cast<float>();
    }
    features_.corners.push_back(corner);
  }
}

const Junction* FeatureExtractor::nearestJunction(const Eigen::Vector2f& position) const {
  const Eigen::Vector2d here = position.cast<double>();
  const double radius = options_.junction_radius_px;
  auto junction =
      std::lower_bound(junctions_by_x_.begin(), junctions_by_x_.end(), here.x() - radius,
                       [](const Junction& j, double x) { return j.position.x() < x; });
  const Junction* nearest = nullptr;
  double nearest_distance = radius;
  for (; junction != junctions_by_x_.end() && junction->position.x() <= here.x() + radius;
       ++junction) {
    const double distance = (junction->position - here).norm();
    if (distance <= nearest_distance) {
      nearest = &*junction;
      nearest_distance = distance;
    }
  }
  return nearest;
}

}  // namespace lineloc
