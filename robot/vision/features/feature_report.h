// What the robot sends, for people: the features of a frame as text and as an
// overlay (segments coloured by polarity, corners as crosses).
#pragma once

#include <opencv2/core.hpp>
#include <ostream>

#include "robot/vision/features/feature_extractor.h"

namespace lineloc {

// One line per feature:
//   segment x1 y1 x2 y2 sigma_offset_px sigma_angle_deg contrast polarity points
//   corner x y cov_xx cov_xy cov_yy strength
void writeFeaturesText(std::ostream& out, const FrameFeatures& features);

// Colour overlay on `undistorted` (grey or BGR): segments with the brighter
// side on the left green, on the right magenta; corners as red crosses.
cv::Mat drawFeatures(const cv::Mat& undistorted, const FrameFeatures& features);

}  // namespace lineloc
