#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "robot/calibration/zhang_calibration.h"
#include "synthetic_views.h"

namespace lineloc {
namespace {

// fx fy cx cy skew k1 k2 p1 p2 k3.
Eigen::Matrix<double, 10, 1> parametersOf(const CameraCalibration& calibration) {
  const PinholeCamera& c = calibration.camera;
  Eigen::Matrix<double, 10, 1> parameters;
  parameters << c.fx, c.fy, c.cx, c.cy, c.skew,
      Eigen::Map<const Eigen::Matrix<double, 5, 1>>(calibration.distortion.data());
  return parameters;
}

Eigen::Matrix<double, 10, 1> stdDevOf(const CalibrationUncertainty& uncertainty) {
  Eigen::Matrix<double, 10, 1> std_dev;
  std_dev << uncertainty.intrinsics_std_dev, uncertainty.distortion_std_dev;
  return std_dev;
}

CalibrationOptions openCvLikeOptions() {
  CalibrationOptions options = openCvCompatibleOptions();
  options.aspect_ratio = 1.02;
  return options;
}

class NoiseFreeCalibration : public ::testing::TestWithParam<CalibrationOptions> {};

// Noise-free views: the optimum is the truth and the solver stops on relative
// tolerances of 1e-12, so every parameter is recovered to 1e-6 relative
// (absolute 1e-9 for the small tangential terms, relative to a floor of 1e-3).
TEST_P(NoiseFreeCalibration, RecoversEveryParameter) {
  const CalibrationOptions options = GetParam();
  const testing::SyntheticViews synthetic = testing::makeSyntheticViews(6, options, 0.0, 1);
  const CalibrationResult result = calibrateCamera(synthetic.views, options);
  ASSERT_EQ(result.status, CalibrationStatus::kConverged) << result.message;
  const Eigen::Matrix<double, 10, 1> truth = parametersOf(synthetic.truth.calibration);
  const Eigen::Matrix<double, 10, 1> estimate = parametersOf(result.state.calibration);
  for (int i = 0; i < 10; ++i) {
    EXPECT_LE(std::abs(estimate(i) - truth(i)), 1e-6 * std::max(std::abs(truth(i)), 1e-3))
        << "parameter " << i << ": " << estimate(i) << " vs " << truth(i);
  }
  for (size_t view = 0; view < synthetic.truth.T_camera_model.size(); ++view) {
    EXPECT_LT(
        (result.state.T_camera_model[view].matrix() - synthetic.truth.T_camera_model[view].matrix())
            .norm(),
        1e-6);
  }
  EXPECT_LT(result.rms_error_px, 1e-6);
  EXPECT_EQ(result.per_view_rms_error_px.size(), 6u);
  EXPECT_TRUE(result.warnings.empty());
}

CalibrationOptions withFixedPrincipalPoint() {
  CalibrationOptions options;
  options.fix_principal_point = true;
  return options;
}

INSTANTIATE_TEST_SUITE_P(Models, NoiseFreeCalibration,
                         ::testing::Values(CalibrationOptions{}, openCvLikeOptions(),
                                           withFixedPrincipalPoint()));

// With Gaussian pixel noise of 0.2 px the estimate is, to first order,
// Gaussian around the truth with the reported covariance, so each normalised
// error z = (estimate - truth) / std_dev is ~N(0, 1): P(|z| > 3) = 0.27 %.
// Over 12 seeds x 10 parameters (120 values, correlated within a seed) we
// require at least 97 % within 3 sigma, none beyond 4.5 sigma (P = 7e-6 each),
// and a mean z^2 in [0.5, 1.6] (chi^2 with 12 independent seeds per
// parameter: the mean of 10 such has a 99.9 % range well inside this).
TEST(ZhangCalibration, NoisyErrorsAgreeWithReportedStandardDeviations) {
  constexpr double kSigmaPx = 0.2;
  constexpr int kSeeds = 12;
  const CalibrationOptions options = [] {
    CalibrationOptions o;
    o.distortion_model = DistortionModel::kOpenCv5;
    return o;
  }();
  int within_3_sigma = 0;
  int count = 0;
  double sum_z2 = 0.0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    const testing::SyntheticViews synthetic =
        testing::makeSyntheticViews(8, options, kSigmaPx, 100u + seed);
    const CalibrationResult result = calibrateCamera(synthetic.views, options);
    ASSERT_EQ(result.status, CalibrationStatus::kConverged) << result.message;
    ASSERT_TRUE(result.uncertainty.available);
    // The estimated noise: sigma^2 chi^2(dof)/dof with dof = 2*8*54 - 58 = 806.
    EXPECT_NEAR(result.uncertainty.noise_sigma_px, kSigmaPx, 0.02);
    const Eigen::Matrix<double, 10, 1> error =
        parametersOf(result.state.calibration) - parametersOf(synthetic.truth.calibration);
    const Eigen::Matrix<double, 10, 1> std_dev = stdDevOf(result.uncertainty);
    for (int i = 0; i < 10; ++i) {
      ASSERT_GT(std_dev(i), 0.0) << i;
      const double z = error(i) / std_dev(i);
      EXPECT_LT(std::abs(z), 4.5) << "seed " << seed << " parameter " << i;
      within_3_sigma += std::abs(z) < 3.0;
      sum_z2 += z * z;
      ++count;
    }
  }
  EXPECT_GE(within_3_sigma, static_cast<int>(0.97 * count));
  EXPECT_GT(sum_z2 / count, 0.5);
  EXPECT_LT(sum_z2 / count, 1.6);
}

TEST(ZhangCalibration, FixedParametersStayFixedWithZeroStdDev) {
  CalibrationOptions options = openCvLikeOptions();
  options.fix_principal_point = true;
  const testing::SyntheticViews synthetic = testing::makeSyntheticViews(5, options, 0.2, 7);
  const CalibrationResult result = calibrateCamera(synthetic.views, options);
  ASSERT_EQ(result.status, CalibrationStatus::kConverged);
  const PinholeCamera& camera = result.state.calibration.camera;
  EXPECT_DOUBLE_EQ(camera.fx / camera.fy, 1.02);
  EXPECT_EQ(camera.cx, 319.5);
  EXPECT_EQ(camera.cy, 239.5);
  EXPECT_EQ(camera.skew, 0.0);
  EXPECT_EQ(result.uncertainty.intrinsics_std_dev(2), 0.0);
  EXPECT_EQ(result.uncertainty.intrinsics_std_dev(4), 0.0);
  EXPECT_DOUBLE_EQ(result.uncertainty.intrinsics_std_dev(1),
                   result.uncertainty.intrinsics_std_dev(0) / 1.02);
}

TEST(ZhangCalibration, RadialModelKeepsTangentialTermsZero) {
  const testing::SyntheticViews synthetic = testing::makeSyntheticViews(5, {}, 0.2, 3);
  const CalibrationResult result = calibrateCamera(synthetic.views, {});
  ASSERT_EQ(result.status, CalibrationStatus::kConverged);
  EXPECT_EQ(result.state.calibration.distortion[2], 0.0);
  EXPECT_EQ(result.state.calibration.distortion[3], 0.0);
  EXPECT_EQ(result.state.calibration.distortion[4], 0.0);
}

TEST(ZhangCalibration, TwoViewsWithZeroSkewCalibrateWithAWarning) {
  const testing::SyntheticViews synthetic = testing::makeTwoViewsWithZeroSkew();
  const CalibrationResult result = calibrateCamera(synthetic.views, {.fix_skew = true});
  ASSERT_EQ(result.status, CalibrationStatus::kConverged);
  ASSERT_FALSE(result.warnings.empty());
  EXPECT_NE(result.warnings[0].find("only 2 views"), std::string::npos);
}

TEST(ZhangCalibration, TwoViewsWithFreeSkewAreNotEnough) {
  const testing::SyntheticViews synthetic = testing::makeSyntheticViews(2, {}, 0.0, 1);
  EXPECT_EQ(calibrateCamera(synthetic.views, {}).status, CalibrationStatus::kNotEnoughViews);
}

TEST(ZhangCalibration, SmallPatternCoverageIsWarned) {
  // Shrink the image of the pattern about the image centre.
  const testing::SyntheticViews small = [] {
    testing::SyntheticViews s = testing::makeSyntheticViews(4, {}, 0.0, 1);
    for (std::vector<Eigen::Vector2d>& points : s.views.image_points) {
      for (Eigen::Vector2d& m : points) {
        m = Eigen::Vector2d(320.0, 240.0) + 0.3 * (m - Eigen::Vector2d(320.0, 240.0));
      }
    }
    return s;
  }();
  const CalibrationResult result = calibrateCamera(small.views, {});
  ASSERT_NE(result.status, CalibrationStatus::kDiverged);
  bool warned = false;
  for (const std::string& warning : result.warnings) {
    warned = warned || warning.find("% of the image") != std::string::npos;
  }
  EXPECT_TRUE(warned);
}

TEST(ZhangCalibration, CollinearViewIsDegenerateAndNamed) {
  testing::SyntheticViews synthetic = testing::makeSyntheticViews(4, {}, 0.0, 1);
  for (Eigen::Vector2d& m : synthetic.views.image_points[2]) {
    m.y() = 100.0;
  }
  const CalibrationResult result = calibrateCamera(synthetic.views, {});
  EXPECT_EQ(result.status, CalibrationStatus::kDegenerate);
  EXPECT_NE(result.message.find("view 2"), std::string::npos);
}

TEST(ZhangCalibration, MalformedViewsThrow) {
  testing::SyntheticViews synthetic = testing::makeSyntheticViews(3, {}, 0.0, 1);
  PlanarViews short_view = synthetic.views;
  short_view.image_points[1].pop_back();
  EXPECT_THROW(calibrateCamera(short_view, {}), std::invalid_argument);
  PlanarViews nan_view = synthetic.views;
  nan_view.image_points[0][5].x() = NAN;
  EXPECT_THROW(calibrateCamera(nan_view, {}), std::invalid_argument);
  PlanarViews no_size = synthetic.views;
  no_size.image_width = 0;
  EXPECT_THROW(calibrateCamera(no_size, {}), std::invalid_argument);
}

TEST(ZhangCalibration, CheckReportsTheErrorOfAKnownCalibrationOnNewViews) {
  CalibrationOptions options;
  options.distortion_model = DistortionModel::kOpenCv5;
  constexpr double kSigmaPx = 0.3;
  const testing::SyntheticViews synthetic = testing::makeSyntheticViews(4, options, kSigmaPx, 11);
  const CalibrationResult check = checkCalibration(synthetic.views, synthetic.truth.calibration);
  ASSERT_EQ(check.status, CalibrationStatus::kConverged) << check.message;
  // Only the 6 pose parameters per view are fitted: rms^2 = sum ||r||^2 / n ~
  // sigma^2 chi^2(2n - 24) / n with n = 216 points, so rms ~ sigma sqrt(408 / 216);
  // chi^2(408) has a relative standard deviation of 7 % (3.5 % on the rms): 12 %
  // is beyond 3 sigma.
  EXPECT_NEAR(check.rms_error_px, kSigmaPx * std::sqrt(408.0 / 216.0), 0.12 * kSigmaPx);
  for (size_t view = 0; view < 4; ++view) {
    EXPECT_LT((check.state.T_camera_model[view].translation() -
               synthetic.truth.T_camera_model[view].translation())
                  .norm(),
              1e-3);
  }
}

}  // namespace
}  // namespace lineloc
