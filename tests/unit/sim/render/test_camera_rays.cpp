#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <random>

#include "sim/render/camera_rays.h"
#include "sim/render/sample_camera.h"

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

TEST(CameraRays, EveryPixelRayProjectsBackToItsPixelWithOpenCv) {
  const CameraCalibration calibration = opencvSampleCamera();
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
  CameraCalibration calibration = opencvSampleCamera();
  calibration.distortion.clear();
  calibration.camera.skew = 0.5;
  const CameraRays rays(calibration);
  const Eigen::Vector3d d = rays.direction(600, 30).cast<double>();
  const Eigen::Vector2d pixel = calibration.camera.project(d);
  EXPECT_NEAR(pixel.x(), 600.0, 1e-3);
  EXPECT_NEAR(pixel.y(), 30.0, 1e-3);
}

TEST(CameraRays, SubPixelRaysProjectBackToTheirPointWithOpenCv) {
  const CameraCalibration calibration = opencvSampleCamera();
  const CameraRays rays(calibration);
  // Inside the image and in its outermost half pixel, where the ray is
  // extrapolated from the last two pixel centres.
  const std::vector<Eigen::Vector2f> points = {
      {0.37f, 0.81f}, {-0.45f, 100.25f}, {320.5f, 240.5f}, {639.45f, 479.3f}, {17.9f, 452.12f}};
  for (const Eigen::Vector2f& point : points) {
    const Eigen::Vector3d d = rays.directionAt(point.x(), point.y()).cast<double>();
    ASSERT_NEAR(d.norm(), 1.0, 1e-6);
    const cv::Point2d pixel = projectWithOpenCv(calibration, d);
    // Bilinear across one pixel of this lens's strongest bend (its corners).
    EXPECT_NEAR(pixel.x, point.x(), 2e-3) << point.transpose();
    EXPECT_NEAR(pixel.y, point.y(), 2e-3) << point.transpose();
  }
}

TEST(CameraRays, RejectsInvalidCamera) {
  CameraCalibration calibration = opencvSampleCamera();
  calibration.camera.fx = 0.0;
  EXPECT_THROW(CameraRays{calibration}, std::invalid_argument);
  calibration = opencvSampleCamera();
  calibration.camera.width = 0;
  EXPECT_THROW(CameraRays{calibration}, std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
