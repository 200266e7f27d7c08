#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "backbone/tracker/tracking_overlay.h"

namespace lineloc {
namespace {

cv::Vec3b pixel(const cv::Mat& image, int x, int y) {
  return image.at<cv::Vec3b>(y, x);
}

// Every image corner is ringed; one the alignment used is filled.
TEST(TrackingOverlay, RingsEveryImageCornerAndFillsThoseTheAlignmentUsed) {
  const cv::Mat image(120, 160, CV_8UC1, cv::Scalar(128));
  CameraCalibration calibration;
  calibration.camera = {
      .fx = 100.0, .fy = 100.0, .cx = 80.0, .cy = 60.0, .width = 160, .height = 120};
  std::vector<ImageCorner> corners(2);
  corners[0].position = {30.0f, 30.0f};
  corners[1].position = {110.0f, 80.0f};
  TrackedFrame frame;
  frame.alignment.status = AlignmentStatus::kOk;
  frame.alignment.inlier_corners = {1};
  const cv::Mat overlay = drawTrackingOverlay(image, {}, corners, frame, calibration);
  const cv::Vec3b background(128, 128, 128);
  // A ring: its centre is left as it was, its edge is drawn.
  EXPECT_EQ(pixel(overlay, 30, 30), background);
  EXPECT_NE(pixel(overlay, 33, 30), background);
  // Filled.
  EXPECT_NE(pixel(overlay, 110, 80), background);
  EXPECT_NE(pixel(overlay, 110, 80), pixel(overlay, 33, 30));
  // Not aligned: nothing was used.
  frame.alignment.status = AlignmentStatus::kFailed;
  EXPECT_EQ(pixel(drawTrackingOverlay(image, {}, corners, frame, calibration), 110, 80),
            background);
}

}  // namespace
}  // namespace lineloc
