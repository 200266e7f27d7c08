#include <gtest/gtest.h>

#include "robot/calibration/distortion_initialisation.h"
#include "synthetic_views.h"

namespace lineloc {
namespace {

// With the true K and poses, D k = d holds exactly (the distortion is linear in
// k), so k is exact up to rounding.
TEST(DistortionInitialisation, RecoversRadialK1K2) {
  const testing::SyntheticViews synthetic = testing::makeSyntheticViews(4, {}, 0.0, 1);
  const std::optional<std::vector<double>> k =
      estimateDistortionLinear(synthetic.views, synthetic.truth.calibration.camera,
                               synthetic.truth.T_camera_model, DistortionModel::kRadialK1K2);
  ASSERT_TRUE(k.has_value());
  ASSERT_EQ(k->size(), 5u);
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR((*k)[i], synthetic.truth.calibration.distortion[i], 1e-10) << i;
  }
}

TEST(DistortionInitialisation, RecoversOpenCvFiveCoefficients) {
  CalibrationOptions options;
  options.distortion_model = DistortionModel::kOpenCv5;
  const testing::SyntheticViews synthetic = testing::makeSyntheticViews(4, options, 0.0, 1);
  const std::optional<std::vector<double>> k =
      estimateDistortionLinear(synthetic.views, synthetic.truth.calibration.camera,
                               synthetic.truth.T_camera_model, DistortionModel::kOpenCv5);
  ASSERT_TRUE(k.has_value());
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR((*k)[i], synthetic.truth.calibration.distortion[i], 1e-9) << i;
  }
}

TEST(DistortionInitialisation, PointsOnTheAxisDoNotDetermineIt) {
  PlanarViews views;
  views.image_width = 640;
  views.image_height = 480;
  views.model_points.assign(4, Eigen::Vector2d::Zero());
  views.image_points = {std::vector<Eigen::Vector2d>(4, Eigen::Vector2d(320.0, 240.0))};
  const PinholeCamera camera{800.0, 800.0, 320.0, 240.0, 0.0, 640, 480};
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation().z() = 1.0;
  EXPECT_FALSE(
      estimateDistortionLinear(views, camera, {T}, DistortionModel::kRadialK1K2).has_value());
}

}  // namespace
}  // namespace lineloc
