#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <random>

#include "sim/render/camera_rays.h"
#include "tests/unit/sim/render/opencv_left_camera.h"

namespace lineloc {
namespace {

cv::Point2d projectWithOpenCv(const CameraCalibration& calibration, const Eigen::Vector3d& p) {
  const cv::Matx33d K(calibration.camera.fx, calibration.camera.skew, calibration.camera.cx, 0.0,
                      calibration.camera.fy, calibration.camera.cy, 0.0, 0.0, 1.0);
  std::vector<cv::Point2d> projected;
  cv::projectPoints(std::vector<cv::Point3d>{{p.x(), p.y(), p.z()}}, cv::Vec3d::zeros(),
                    cv::Vec3d::zeros(), K, calibration.distortion, projected);
  return projected[0];
}

TEST(LensDistortion, ForwardModelMatchesOpenCvProjectPoints) {
  const CameraCalibration calibration = opencvLeftCamera();
  const LensDistortion lens(calibration.distortion);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-0.7, 0.7);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector2d x(coordinate(random), coordinate(random));
    const Eigen::Vector2d x_d = lens.distort(x);
    const cv::Point2d expected = projectWithOpenCv(calibration, {x.x(), x.y(), 1.0});
    // Same closed-form model in double precision: only rounding differs (~1e-13 px).
    EXPECT_NEAR(calibration.camera.fx * x_d.x() + calibration.camera.cx, expected.x, 1e-9);
    EXPECT_NEAR(calibration.camera.fy * x_d.y() + calibration.camera.cy, expected.y, 1e-9);
  }
}

TEST(LensDistortion, RationalAndTangentialModelMatchesOpenCv) {
  CameraCalibration calibration = opencvLeftCamera();
  calibration.distortion = {0.1, -0.05, 2e-3, -1e-3, 0.01, 0.08, -0.02, 0.005};
  const LensDistortion lens(calibration.distortion);
  for (double x = -0.6; x <= 0.6; x += 0.1) {
    for (double y = -0.45; y <= 0.45; y += 0.15) {
      const Eigen::Vector2d x_d = lens.distort({x, y});
      const cv::Point2d expected = projectWithOpenCv(calibration, {x, y, 1.0});
      EXPECT_NEAR(calibration.camera.fx * x_d.x() + calibration.camera.cx, expected.x, 1e-9);
      EXPECT_NEAR(calibration.camera.fy * x_d.y() + calibration.camera.cy, expected.y, 1e-9);
    }
  }
}

TEST(LensDistortion, UndistortInvertsDistort) {
  const LensDistortion lens(opencvLeftCamera().distortion);
  for (double x = -0.65; x <= 0.65; x += 0.05) {
    for (double y = -0.5; y <= 0.5; y += 0.05) {
      Eigen::Vector2d undistorted;
      ASSERT_TRUE(lens.undistort(lens.distort({x, y}), undistorted));
      // Gauss-Newton stops at a residual of 1e-12; the Jacobian is near 1.
      EXPECT_NEAR(undistorted.x(), x, 1e-10);
      EXPECT_NEAR(undistorted.y(), y, 1e-10);
    }
  }
}

TEST(LensDistortion, RejectsTooManyCoefficients) {
  EXPECT_THROW(LensDistortion(std::vector<double>(9, 0.0)), std::invalid_argument);
}

TEST(CameraRays, EveryPixelRayProjectsBackToItsPixelWithOpenCv) {
  const CameraCalibration calibration = opencvLeftCamera();
  const CameraRays rays(calibration);
  ASSERT_EQ(rays.invalidCount(), 0);
  for (int v = 0; v < rays.height(); v += 7) {
    for (int u = 0; u < rays.width(); u += 7) {
      const Eigen::Vector3d d = rays.direction(u, v).cast<double>();
      ASSERT_NEAR(d.norm(), 1.0, 1e-6);
      const cv::Point2d pixel = projectWithOpenCv(calibration, d);
      // Directions are stored as float (relative error 6e-8, ~5e-5 px at the
      // image corner where d/dx of the projection is ~ 800 px).
      EXPECT_NEAR(pixel.x, u, 1e-3) << "pixel " << u << "," << v;
      EXPECT_NEAR(pixel.y, v, 1e-3) << "pixel " << u << "," << v;
    }
  }
}

TEST(CameraRays, PinholeRaysAreInverseIntrinsics) {
  CameraCalibration calibration = opencvLeftCamera();
  calibration.distortion.clear();
  calibration.camera.skew = 0.5;
  const CameraRays rays(calibration);
  const Eigen::Vector3d d = rays.direction(600, 30).cast<double>();
  const Eigen::Vector2d pixel = calibration.camera.project(d);
  EXPECT_NEAR(pixel.x(), 600.0, 1e-3);
  EXPECT_NEAR(pixel.y(), 30.0, 1e-3);
}

TEST(CameraRays, RejectsInvalidCamera) {
  CameraCalibration calibration = opencvLeftCamera();
  calibration.camera.fx = 0.0;
  EXPECT_THROW(CameraRays{calibration}, std::invalid_argument);
  calibration = opencvLeftCamera();
  calibration.camera.width = 0;
  EXPECT_THROW(CameraRays{calibration}, std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
