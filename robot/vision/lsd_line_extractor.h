// First line extractor of the robot: OpenCV's LSD (von Gioi et al., "LSD: a
// Line Segment Detector", IPOL 2012) on the undistorted image.
//
// The image is undistorted with maps built once from the calibration, so the
// segments are in undistorted pixel coordinates of the calibrated camera, as
// the LineSet requires. Endpoint covariance: sigma_normal = max(0.5, w/4) px
// across the line (w: LSD's region width), sigma_along = 1 px along it.
// Polarity and contrast come from the mean grey levels sampled 2 px either side.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "common/camera/camera_calibration.h"
#include "common/messages/messages.h"

namespace lineloc {

class LsdLineExtractor {
 public:
  LsdLineExtractor(const CameraCalibration& calibration, double min_length_px);

  // `grey` must be 8-bit single channel of the calibration's size; throws
  // std::invalid_argument otherwise.
  std::vector<ImageSegment> extract(const cv::Mat& grey);

 private:
  ImageSegment describe(const cv::Vec4f& line, double width) const;

  CameraCalibration calibration_;
  double min_length_px_;
  cv::Ptr<cv::LineSegmentDetector> detector_;
  cv::Mat undistort_map_x_, undistort_map_y_;
  cv::Mat undistorted_;
};

}  // namespace lineloc
