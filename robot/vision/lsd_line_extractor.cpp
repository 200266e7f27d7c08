#include "robot/vision/lsd_line_extractor.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <stdexcept>

namespace lineloc {
namespace {

constexpr double kSideOffsetPx = 2.0;
constexpr int kSamplesPerSide = 8;
constexpr float kSigmaAlongPx = 1.0f;

// Endpoint covariance with sigma_normal across and sigma_along along direction d.
Eigen::Matrix2f endpointCovariance(const Eigen::Vector2f& d, float sigma_normal) {
  const Eigen::Vector2f n(-d.y(), d.x());
  return sigma_normal * sigma_normal * n * n.transpose() +
         kSigmaAlongPx * kSigmaAlongPx * d * d.transpose();
}

float bilinear(const cv::Mat& grey, float x, float y) {
  x = std::clamp(x, 0.0f, static_cast<float>(grey.cols - 1));
  y = std::clamp(y, 0.0f, static_cast<float>(grey.rows - 1));
  const int x0 = std::min(static_cast<int>(x), grey.cols - 2);
  const int y0 = std::min(static_cast<int>(y), grey.rows - 2);
  const float ax = x - x0;
  const float ay = y - y0;
  const auto at = [&](int r, int c) { return static_cast<float>(grey.at<uint8_t>(r, c)); };
  return (1 - ay) * ((1 - ax) * at(y0, x0) + ax * at(y0, x0 + 1)) +
         ay * ((1 - ax) * at(y0 + 1, x0) + ax * at(y0 + 1, x0 + 1));
}

}  // namespace

LsdLineExtractor::LsdLineExtractor(const CameraCalibration& calibration, double min_length_px)
    : calibration_(calibration),
      min_length_px_(min_length_px),
      detector_(cv::createLineSegmentDetector(cv::LSD_REFINE_STD)) {
  const PinholeCamera& camera = calibration.camera;
  if (!calibration.distortion.empty()) {
    cv::Mat K;
    cv::eigen2cv(camera.K(), K);
    cv::initUndistortRectifyMap(K, calibration.distortion, cv::Mat(), K,
                                cv::Size(camera.width, camera.height), CV_32FC1,
                                undistort_map_x_, undistort_map_y_);
  }
}

std::vector<ImageSegment> LsdLineExtractor::extract(const cv::Mat& grey) {
  const PinholeCamera& camera = calibration_.camera;
  if (grey.type() != CV_8UC1) {
    throw std::invalid_argument("line extractor needs an 8-bit single-channel image");
  }
  if (grey.cols != camera.width || grey.rows != camera.height) {
    throw std::invalid_argument(fmt::format("image is {}x{}, the calibration is for {}x{}",
                                            grey.cols, grey.rows, camera.width, camera.height));
  }
  if (undistort_map_x_.empty()) {
    undistorted_ = grey;
  } else {
    cv::remap(grey, undistorted_, undistort_map_x_, undistort_map_y_, cv::INTER_LINEAR);
  }
  std::vector<cv::Vec4f> lines;
  std::vector<double> widths;
  detector_->detect(undistorted_, lines, widths);
  std::vector<ImageSegment> segments;
  for (size_t i = 0; i < lines.size(); ++i) {
    const cv::Vec4f& line = lines[i];
    if (std::hypot(line[2] - line[0], line[3] - line[1]) >= min_length_px_) {
      segments.push_back(describe(line, widths.empty() ? 1.0 : widths[i]));
    }
  }
  return segments;
}

ImageSegment LsdLineExtractor::describe(const cv::Vec4f& line, double width) const {
  ImageSegment segment;
  segment.start = {line[0], line[1]};
  segment.end = {line[2], line[3]};
  const Eigen::Vector2f direction = (segment.end - segment.start).normalized();
  // Left of start -> end in an image with y down.
  const Eigen::Vector2f left(direction.y(), -direction.x());
  const float sigma_normal = std::max(0.5f, static_cast<float>(width) / 4.0f);
  segment.start_covariance = endpointCovariance(direction, sigma_normal);
  segment.end_covariance = segment.start_covariance;
  float left_sum = 0.0f;
  float right_sum = 0.0f;
  for (int k = 0; k < kSamplesPerSide; ++k) {
    const float t = (k + 0.5f) / kSamplesPerSide;
    const Eigen::Vector2f p = segment.start + t * (segment.end - segment.start);
    const Eigen::Vector2f l = p + kSideOffsetPx * left;
    const Eigen::Vector2f r = p - kSideOffsetPx * left;
    left_sum += bilinear(undistorted_, l.x(), l.y());
    right_sum += bilinear(undistorted_, r.x(), r.y());
  }
  const float difference = (left_sum - right_sum) / kSamplesPerSide;
  segment.contrast = std::abs(difference);
  segment.polarity = difference > 0.0f ? 1 : (difference < 0.0f ? -1 : 0);
  return segment;
}

}  // namespace lineloc
