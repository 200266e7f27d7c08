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

}  // namespace
}  // namespace lineloc
