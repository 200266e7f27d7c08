// A whole image undistorted onto the calibration's undistorted camera
// (camera_calibration.h), for display: overlays draw the robot's undistorted
// lines on it. OpenCV's cv::undistort for a radial-tangential lens,
// cv::fisheye::undistortImage for an equidistant one; a fisheye's pixels
// beyond the view are black.
#pragma once

#include <opencv2/core.hpp>

#include "common/camera/camera_calibration.h"

namespace lineloc {

cv::Mat undistortImage(const cv::Mat& image, const CameraCalibration& calibration);

}  // namespace lineloc
