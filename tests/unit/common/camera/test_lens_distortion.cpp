#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <vector>

#include "common/camera/lens_distortion.h"

namespace lineloc {
namespace {

const std::vector<double> kOpenCvLeftDistortion = {-0.2658, -0.0467, 0.0018, -0.0003, 0.2523};

TEST(LensDistortion, NoCoefficientsIsIdentity) {
  const Eigen::Vector2d x(0.3, -0.2);
  EXPECT_EQ(distortNormalised(x, {}), x);
}

// OpenCV's cv::projectPoints with K = I is the reference implementation of
// the same model; both evaluate the same polynomial in double precision.
TEST(LensDistortion, MatchesOpenCvProjection) {
  const std::vector<std::vector<double>> models = {
      {0.1, -0.05, 0.0, 0.0},
      kOpenCvLeftDistortion,
      {0.2, 0.01, 0.001, -0.002, 0.003, 0.05, -0.01, 0.002}};
  for (const std::vector<double>& coefficients : models) {
    std::vector<cv::Point3d> points;
    for (double x = -0.5; x <= 0.5; x += 0.25) {
      for (double y = -0.4; y <= 0.4; y += 0.2) {
        points.emplace_back(x, y, 1.0);
      }
    }
    std::vector<cv::Point2d> projected;
    cv::projectPoints(points, cv::Vec3d::zeros(), cv::Vec3d::zeros(), cv::Matx33d::eye(),
                      coefficients, projected);
    for (size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector2d distorted =
          distortNormalised(Eigen::Vector2d(points[i].x, points[i].y), coefficients);
      EXPECT_NEAR(distorted.x(), projected[i].x, 1e-12);
      EXPECT_NEAR(distorted.y(), projected[i].y, 1e-12);
    }
  }
}

TEST(LensDistortion, UndistortInvertsDistort) {
  for (double x = -0.6; x <= 0.6; x += 0.1) {
    for (double y = -0.45; y <= 0.45; y += 0.15) {
      const Eigen::Vector2d undistorted(x, y);
      const std::optional<Eigen::Vector2d> recovered = undistortNormalised(
          distortNormalised(undistorted, kOpenCvLeftDistortion), kOpenCvLeftDistortion);
      ASSERT_TRUE(recovered.has_value()) << x << " " << y;
      EXPECT_LT((*recovered - undistorted).norm(), 1e-10);
    }
  }
}

TEST(LensDistortion, UndistortReportsPointsOutsideTheInvertibleRegion) {
  // x_d = x (1 - r^2) peaks at x_d = 0.385; larger x_d have no preimage.
  EXPECT_FALSE(undistortNormalised(Eigen::Vector2d(0.9, 0.0), {-1.0, 0.0}).has_value());
  EXPECT_FALSE(undistortNormalised(Eigen::Vector2d(NAN, 0.0), {-0.1, 0.0}).has_value());
}

// The equidistant model (Kannala & Brandt eq. 6) as cv::fisheye projects,
// inverted to the ray, out to rays beyond 90 degrees off the axis.
TEST(LensDistortion, EquidistantMatchesOpenCvsFisheyeAndInverts) {
  const std::vector<double> k = {0.015, -0.006, 0.001, -0.0002};
  for (const Eigen::Vector3d& ray :
       {Eigen::Vector3d(0.2, -0.1, 1.0), Eigen::Vector3d(1.0, 0.5, 0.3),
        Eigen::Vector3d(-0.4, 0.9, 0.05)}) {
    std::vector<cv::Point2d> projected;
    cv::fisheye::projectPoints(std::vector<cv::Point3d>{{ray.x(), ray.y(), ray.z()}}, projected,
                               cv::Vec3d::all(0.0), cv::Vec3d::all(0.0), cv::Matx33d::eye(), k);
    const Eigen::Vector2d distorted = distortEquidistant(ray, k);
    EXPECT_NEAR(distorted.x(), projected[0].x, 1e-12);
    EXPECT_NEAR(distorted.y(), projected[0].y, 1e-12);
    const std::optional<Eigen::Vector3d> back = undistortEquidistant(distorted, k);
    ASSERT_TRUE(back);
    EXPECT_LT((*back - ray.normalized()).norm(), 1e-9);
  }
  const Eigen::Vector2d behind = distortEquidistant(Eigen::Vector3d(1.0, 0.0, -0.2), k);
  const std::optional<Eigen::Vector3d> back = undistortEquidistant(behind, k);
  ASSERT_TRUE(back);
  EXPECT_LT(back->z(), 0.0);
  EXPECT_FALSE(undistortEquidistant({40.0, 0.0}, k));  // beyond where the model increases
}

}  // namespace
}  // namespace lineloc
