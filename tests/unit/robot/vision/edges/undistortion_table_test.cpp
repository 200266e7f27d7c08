#include "robot/vision/edges/undistortion_table.h"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <random>

namespace lineloc {
namespace {

CameraCalibration leftCamera() {
  // OpenCV's calibration of its left*.jpg views (opencv-doc left_intrinsics.yml).
  CameraCalibration calibration;
  calibration.camera = {535.9157, 535.9157, 342.2832, 235.5708, 0.0, 640, 480};
  calibration.distortion = {-0.2663, -0.0387, 0.00178, -0.00028, 0.2389};
  return calibration;
}

TEST(UndistortionTable, NoDistortionIsTheIdentity) {
  CameraCalibration calibration = leftCamera();
  calibration.distortion = {0.0, 0.0, 0.0, 0.0};
  const UndistortionTable table(calibration);
  EXPECT_TRUE(table.isIdentity());
  EXPECT_EQ(table.undistort({12.25f, 300.5f}), Eigen::Vector2f(12.25f, 300.5f));
}

// Bilinear interpolation error <= (1/8) max|u''| px^2; the radial model's
// second derivative in pixels is ~2 k1 / f ~ 1e-3 / px near the border of a
// 640 x 480 image, so the table agrees with OpenCV's iterative inverse to
// ~1e-4 px; 2e-3 px allows for float storage of coordinates up to 640.
TEST(UndistortionTable, MatchesOpenCvAtSubPixelPositions) {
  const CameraCalibration calibration = leftCamera();
  const UndistortionTable table(calibration);
  ASSERT_FALSE(table.isIdentity());
  std::mt19937 random(5);
  std::uniform_real_distribution<float> x(0.0f, 639.0f), y(0.0f, 479.0f);
  std::vector<cv::Point2f> points;
  for (int i = 0; i < 500; ++i) {
    points.emplace_back(x(random), y(random));
  }
  const cv::Matx33d K(535.9157, 0.0, 342.2832, 0.0, 535.9157, 235.5708, 0.0, 0.0, 1.0);
  std::vector<cv::Point2f> expected;
  cv::undistortPoints(points, expected, K, calibration.distortion, cv::noArray(), K,
                      cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-9));
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2f u = table.undistort({points[i].x, points[i].y});
    EXPECT_NEAR(u.x(), expected[i].x, 2e-3) << i;
    EXPECT_NEAR(u.y(), expected[i].y, 2e-3) << i;
  }
}

// The Jacobian is the table's own slope: central differences of undistort()
// over +-0.25 px inside one cell agree to float rounding.
TEST(UndistortionTable, JacobianIsTheSlopeOfTheTable) {
  const UndistortionTable table(leftCamera());
  const Eigen::Vector2f p(20.5f, 30.5f);
  const Eigen::Matrix2f J = table.jacobian(p);
  const float h = 0.25f;
  const Eigen::Vector2f dx =
      (table.undistort(p + Eigen::Vector2f(h, 0)) - table.undistort(p - Eigen::Vector2f(h, 0))) /
      (2 * h);
  const Eigen::Vector2f dy =
      (table.undistort(p + Eigen::Vector2f(0, h)) - table.undistort(p - Eigen::Vector2f(0, h))) /
      (2 * h);
  EXPECT_LT((J.col(0) - dx).norm(), 1e-3f);
  EXPECT_LT((J.col(1) - dy).norm(), 1e-3f);
  EXPECT_GT((J - Eigen::Matrix2f::Identity()).norm(), 1e-3f);  // distortion is felt
}

// A fisheye's table agrees with OpenCV's cv::fisheye inverse onto the same
// K within the undistorted view (tolerance as above, its second derivative
// being larger towards the view's edge), and holds NaN where a ray lies
// outside the image's rectangle or 90 degrees or more off the axis, and only
// near or beyond the view's edge.
TEST(UndistortionTable, AFisheyeMatchesOpenCvsFisheyeWithinItsView) {
  CameraCalibration fisheye;
  fisheye.camera = {200.0, 200.0, 319.5, 239.5, 0.0, 640, 480};
  fisheye.distortion = {0.015, -0.006, 0.001, -0.0002};
  fisheye.lens = LensModel::kEquidistant;
  const UndistortionTable table(fisheye);
  ASSERT_FALSE(table.isIdentity());
  const cv::Matx33d K(200.0, 0.0, 319.5, 0.0, 200.0, 239.5, 0.0, 0.0, 1.0);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> x(0.0f, 639.0f), y(0.0f, 479.0f);
  int inside = 0, outside = 0;
  for (int i = 0; i < 2000; ++i) {
    const cv::Point2f p(x(random), y(random));
    std::vector<cv::Point2f> expected;
    cv::fisheye::undistortPoints(std::vector<cv::Point2f>{p}, expected, K, fisheye.distortion,
                                 cv::noArray(), K);
    const Eigen::Vector2f u = table.undistort({p.x, p.y});
    const double offset_deg = std::hypot(p.x - 319.5, p.y - 239.5) / 200.0 * 180.0 / M_PI;
    // Well inside: a pixel of the lens next to the view's edge spreads over
    // many of the undistorted view's there, and a cell with a NaN corner
    // interpolates to NaN.
    const bool in_view = expected[0].x > 20.0f && expected[0].x < 619.0f && expected[0].y > 20.0f &&
                         expected[0].y < 459.0f && offset_deg < 80.0;
    if (u.allFinite()) {
      ++inside;
      EXPECT_NEAR(u.x(), expected[0].x, 2e-2) << p;
      EXPECT_NEAR(u.y(), expected[0].y, 2e-2) << p;
    } else {
      ++outside;
      EXPECT_FALSE(in_view) << p << " -> " << expected[0];
    }
  }
  EXPECT_GT(inside, 500);
  EXPECT_GT(outside, 500);
}

}  // namespace
}  // namespace lineloc
