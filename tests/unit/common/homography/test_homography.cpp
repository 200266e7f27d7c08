#include "common/homography/homography.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

namespace lineloc {
namespace {

// A 9x6 chessboard with 25 mm squares (metres), Z = 0.
std::vector<Eigen::Vector2d> boardPoints() {
  std::vector<Eigen::Vector2d> points;
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 9; ++col) {
      points.emplace_back(0.025 * col, 0.025 * row);
    }
  }
  return points;
}

// H = K [r1 r2 t] for a camera 0.5 m in front of the board, tilted by `tilt_rad`.
Eigen::Matrix3d viewHomography(double tilt_rad, const Eigen::Vector3d& axis) {
  Eigen::Matrix3d K;
  K << 800.0, 0.5, 320.0, 0.0, 780.0, 240.0, 0.0, 0.0, 1.0;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(tilt_rad, axis.normalized()).toRotationMatrix();
  const Eigen::Vector3d t(-0.1, -0.06, 0.5);
  Eigen::Matrix3d Rt;
  Rt << R.col(0), R.col(1), t;
  const Eigen::Matrix3d H = K * Rt;
  return H / H(2, 2);
}

std::vector<Eigen::Vector2d> project(const Eigen::Matrix3d& H,
                                     const std::vector<Eigen::Vector2d>& model) {
  std::vector<Eigen::Vector2d> image;
  for (const Eigen::Vector2d& M : model) {
    image.push_back(applyHomography(H, M));
  }
  return image;
}

class HomographyViews : public ::testing::TestWithParam<int> {
 protected:
  Eigen::Matrix3d trueH() const {
    const double tilt_rad = 0.15 * GetParam();
    return viewHomography(tilt_rad, Eigen::Vector3d(1.0, 0.3 * GetParam(), 0.2));
  }
};

TEST_P(HomographyViews, DltRecoversNoiseFreeHomography) {
  const std::vector<Eigen::Vector2d> model = boardPoints();
  const Eigen::Matrix3d H_true = trueH();
  const HomographyEstimate estimate = estimateHomographyDlt(model, project(H_true, model));
  ASSERT_EQ(estimate.status, HomographyStatus::kOk);
  // Exact data: only rounding (~1e-16 relative, amplified by the SVD's condition).
  EXPECT_LT((estimate.H - H_true).norm() / H_true.norm(), 1e-9);
  EXPECT_LT(estimate.rms_error, 1e-8);
  EXPECT_DOUBLE_EQ(estimate.H(2, 2), 1.0);
}

TEST_P(HomographyViews, RefinementConvergesFromPerturbedStart) {
  const std::vector<Eigen::Vector2d> model = boardPoints();
  const Eigen::Matrix3d H_true = trueH();
  Eigen::Matrix3d H_start = H_true;
  H_start(0, 0) *= 1.02;
  H_start(1, 2) += 3.0;
  H_start(2, 0) += 0.05;
  const HomographyEstimate estimate = refineHomography(model, project(H_true, model), H_start);
  ASSERT_EQ(estimate.status, HomographyStatus::kOk);
  EXPECT_LT((estimate.H - H_true).norm() / H_true.norm(), 1e-9);
  EXPECT_LT(estimate.rms_error, 1e-8);
}

// With i.i.d. Gaussian noise sigma on the n image points, the maximum-likelihood
// fit moves the 2n residuals into the 8-dimensional tangent space of the model,
// so (first order): sum_i ||proj(H_est M_i) - proj(H_true M_i)||^2 ~ sigma^2
// chi^2(8), and rms_error^2 ~ sigma^2 chi^2(2n - 8) / n. The tolerances are the
// 0.1 % and 99.9 % quantiles of those distributions.
TEST_P(HomographyViews, NoisyEstimateIsWithinNoiseModel) {
  constexpr double kSigmaPx = 0.5;
  const std::vector<Eigen::Vector2d> model = boardPoints();
  const Eigen::Matrix3d H_true = trueH();
  std::vector<Eigen::Vector2d> image = project(H_true, model);
  std::mt19937 random(1000u + static_cast<unsigned>(GetParam()));
  std::normal_distribution<double> noise(0.0, kSigmaPx);
  for (Eigen::Vector2d& m : image) {
    m += Eigen::Vector2d(noise(random), noise(random));
  }
  const HomographyEstimate dlt = estimateHomographyDlt(model, image);
  const HomographyEstimate estimate = estimateHomography(model, image);
  ASSERT_EQ(estimate.status, HomographyStatus::kOk);
  EXPECT_LE(estimate.rms_error, dlt.rms_error + 1e-12);

  double transfer_squared = 0.0;
  for (const Eigen::Vector2d& M : model) {
    transfer_squared += (applyHomography(estimate.H, M) - applyHomography(H_true, M)).squaredNorm();
  }
  constexpr double kChi2Dof8Quantile999 = 26.12;
  EXPECT_LT(transfer_squared, kChi2Dof8Quantile999 * kSigmaPx * kSigmaPx);

  // chi^2(100) quantiles 0.1 % and 99.9 %: 61.9 and 149.4; n = 54.
  const double n = static_cast<double>(model.size());
  EXPECT_GT(estimate.rms_error * estimate.rms_error, 61.9 / n * kSigmaPx * kSigmaPx);
  EXPECT_LT(estimate.rms_error * estimate.rms_error, 149.4 / n * kSigmaPx * kSigmaPx);
}

INSTANTIATE_TEST_SUITE_P(Tilts, HomographyViews, ::testing::Values(0, 1, 2, 3, 4));

TEST(Homography, FourPointsGiveExactHomography) {
  const std::vector<Eigen::Vector2d> model = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Eigen::Vector2d> image = {{10, 20}, {110, 25}, {105, 130}, {5, 118}};
  const HomographyEstimate estimate = estimateHomography(model, image);
  ASSERT_EQ(estimate.status, HomographyStatus::kOk);
  for (size_t i = 0; i < model.size(); ++i) {
    EXPECT_LT((applyHomography(estimate.H, model[i]) - image[i]).norm(), 1e-9);
  }
}

TEST(Homography, FewerThanFourPointsAreNotEnough) {
  const std::vector<Eigen::Vector2d> model = {{0, 0}, {1, 0}, {1, 1}};
  EXPECT_EQ(estimateHomography(model, model).status, HomographyStatus::kNotEnoughPoints);
  EXPECT_EQ(estimateHomography({}, {}).status, HomographyStatus::kNotEnoughPoints);
}

TEST(Homography, CollinearModelPointsAreDegenerate) {
  const std::vector<Eigen::Vector2d> model = {{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 4}};
  const std::vector<Eigen::Vector2d> image = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {2, 3}};
  EXPECT_EQ(estimateHomography(model, image).status, HomographyStatus::kDegenerate);
  EXPECT_EQ(estimateHomography(image, model).status, HomographyStatus::kDegenerate);
}

TEST(Homography, CoincidentPointsAreDegenerate) {
  const std::vector<Eigen::Vector2d> same(6, Eigen::Vector2d(3.0, 4.0));
  const std::vector<Eigen::Vector2d> image = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {2, 3}, {5, 1}};
  EXPECT_EQ(estimateHomography(same, image).status, HomographyStatus::kDegenerate);
}

TEST(Homography, FourPointsWithThreeCollinearAreDegenerate) {
  const std::vector<Eigen::Vector2d> model = {{0, 0}, {1, 0}, {2, 0}, {0, 1}};
  const std::vector<Eigen::Vector2d> image = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_EQ(estimateHomography(model, image).status, HomographyStatus::kDegenerate);
}

TEST(Homography, NonFiniteInputIsReported) {
  std::vector<Eigen::Vector2d> model = boardPoints();
  std::vector<Eigen::Vector2d> image =
      project(viewHomography(0.2, Eigen::Vector3d::UnitX()), model);
  image[7].x() = std::nan("");
  EXPECT_EQ(estimateHomography(model, image).status, HomographyStatus::kNonFinite);
  image[7].x() = 1.0;
  model[3].y() = INFINITY;
  EXPECT_EQ(estimateHomography(model, image).status, HomographyStatus::kNonFinite);
  EXPECT_EQ(refineHomography(boardPoints(), image, Eigen::Matrix3d::Constant(NAN)).status,
            HomographyStatus::kNonFinite);
}

TEST(Homography, SingularStartIsDegenerate) {
  const std::vector<Eigen::Vector2d> model = boardPoints();
  const std::vector<Eigen::Vector2d> image =
      project(viewHomography(0.2, Eigen::Vector3d::UnitX()), model);
  Eigen::Matrix3d H_singular = Eigen::Matrix3d::Zero();
  H_singular(0, 0) = H_singular(1, 1) = 1.0;
  EXPECT_EQ(refineHomography(model, image, H_singular).status, HomographyStatus::kDegenerate);
}

TEST(Homography, MismatchedListsThrow) {
  const std::vector<Eigen::Vector2d> model = boardPoints();
  const std::vector<Eigen::Vector2d> image(model.size() - 1, Eigen::Vector2d::Zero());
  EXPECT_THROW(estimateHomography(model, image), std::invalid_argument);
  EXPECT_THROW(estimateHomographyDlt(model, image), std::invalid_argument);
}

TEST(Homography, StatusesHaveNames) {
  EXPECT_STREQ(toString(HomographyStatus::kOk), "ok");
  EXPECT_NE(std::string(toString(HomographyStatus::kDegenerate)).find("degenerate"),
            std::string::npos);
}

}  // namespace
}  // namespace lineloc
