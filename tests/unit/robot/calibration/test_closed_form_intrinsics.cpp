#include <gtest/gtest.h>

#include "robot/calibration/closed_form_intrinsics.h"
#include "synthetic_views.h"

namespace lineloc {
namespace {

std::vector<Eigen::Matrix3d> homographiesOf(const testing::SyntheticViews& synthetic) {
  std::vector<Eigen::Matrix3d> homographies;
  for (const Eigen::Isometry3d& T : synthetic.truth.T_camera_model) {
    homographies.push_back(testing::viewHomography(synthetic.truth.calibration.camera, T));
  }
  return homographies;
}

// Exact homographies: K is exact up to rounding in the SVD (condition of V ~1e4
// after normalisation), so 1e-9 relative.
TEST(ClosedFormIntrinsics, RecoversKWithSkewFromExactHomographies) {
  const testing::SyntheticViews synthetic = testing::makeSyntheticViews(5, {}, 0.0, 1);
  const ClosedFormIntrinsics estimate =
      estimateIntrinsicsClosedForm(homographiesOf(synthetic), false, 640, 480);
  ASSERT_EQ(estimate.status, ClosedFormStatus::kOk);
  const Eigen::Matrix3d K = synthetic.truth.calibration.camera.K();
  EXPECT_LT((estimate.K - K).norm() / K.norm(), 1e-9);
  EXPECT_NEAR(estimate.K(0, 1), 0.4, 1e-6);
}

TEST(ClosedFormIntrinsics, TwoViewsSufficeWithZeroSkew) {
  const testing::SyntheticViews synthetic = testing::makeTwoViewsWithZeroSkew();
  const ClosedFormIntrinsics estimate =
      estimateIntrinsicsClosedForm(homographiesOf(synthetic), true, 640, 480);
  ASSERT_EQ(estimate.status, ClosedFormStatus::kOk);
  const Eigen::Matrix3d K = synthetic.truth.calibration.camera.K();
  EXPECT_LT((estimate.K - K).norm() / K.norm(), 1e-9);
  EXPECT_EQ(estimate.K(0, 1), 0.0);
}

TEST(ClosedFormIntrinsics, TooFewViewsAreReported) {
  const testing::SyntheticViews synthetic = testing::makeSyntheticViews(2, {}, 0.0, 1);
  EXPECT_EQ(estimateIntrinsicsClosedForm(homographiesOf(synthetic), false, 640, 480).status,
            ClosedFormStatus::kNotEnoughViews);
  EXPECT_EQ(estimateIntrinsicsClosedForm({homographiesOf(synthetic)[0]}, true, 640, 480).status,
            ClosedFormStatus::kNotEnoughViews);
}

// Parallel planes (pure translations of one view) give the same two equations
// again (Zhang §3.1): V has rank 2.
TEST(ClosedFormIntrinsics, ParallelPlanesAreDegenerate) {
  testing::SyntheticViews synthetic = testing::makeSyntheticViews(1, {}, 0.0, 1);
  const Eigen::Isometry3d first = synthetic.truth.T_camera_model[0];
  for (int view = 1; view < 4; ++view) {
    Eigen::Isometry3d moved = first;
    moved.translation() += Eigen::Vector3d(0.02 * view, -0.01 * view, 0.05 * view);
    synthetic.truth.T_camera_model.push_back(moved);
  }
  EXPECT_EQ(estimateIntrinsicsClosedForm(homographiesOf(synthetic), false, 640, 480).status,
            ClosedFormStatus::kDegenerate);
}

}  // namespace
}  // namespace lineloc
