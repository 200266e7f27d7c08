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
