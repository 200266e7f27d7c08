#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "common/geometry/pose.h"

namespace lineloc {
namespace {

// An estimate moved by e = [dp; dtheta] (t = t_est + dp, R = Exp(dtheta) R_est)
// gives e back.
TEST(Pose, ErrorIsTheLeftPerturbationFromEstimateToTruth) {
  const Eigen::Isometry3d estimate = makePose(
      {4.0, -2.0, 1.5},
      Eigen::Quaterniond(Eigen::AngleAxisd(0.8, Eigen::Vector3d(1.0, 2.0, -1.0).normalized())));
  Eigen::Matrix<double, 6, 1> error;
  error << 0.05, -0.02, 0.01, 0.003, -0.004, 0.01;
  const Eigen::Isometry3d truth = applyPoseError(estimate, error);
  EXPECT_TRUE(truth.translation().isApprox(estimate.translation() + error.head<3>(), 1e-15));
  EXPECT_TRUE(truth.linear().isApprox(
      Eigen::AngleAxisd(error.tail<3>().norm(), error.tail<3>().normalized()) * estimate.linear(),
      1e-15));
  EXPECT_TRUE(poseError(estimate, truth).isApprox(error, 1e-12));
  EXPECT_TRUE(applyPoseError(estimate, Eigen::Matrix<double, 6, 1>::Zero()).isApprox(estimate));
}

// Fusing two estimates whose covariances are diagonal is the per-axis
// inverse-variance mean: a 2 cm estimate and a 4 cm one 5 cm apart in x give
// x moved 4^2 / (2^2 + 4^2) = 0.2 of the way, sigma 2 * 4 / sqrt(20) cm; in an
// axis where one is a hundred times surer, the fused one follows it.
TEST(Pose, FusingIsTheInverseVarianceMeanPerAxis) {
  PoseWithCovariance a;
  a.pose = makePose({1.0, 2.0, 3.0}, Eigen::Quaterniond::Identity());
  a.covariance = diagonalPoseCovariance(0.02, 0.001);
  PoseWithCovariance b = a;
  b.covariance = diagonalPoseCovariance(0.04, 0.1);
  b.pose.translation().x() += 0.05;
  b.pose.linear() = Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const PoseWithCovariance fused = fusePoses(a, b);
  EXPECT_NEAR(fused.pose.translation().x(), 1.0 + 0.2 * 0.05, 1e-12);
  EXPECT_NEAR(fused.pose.translation().y(), 2.0, 1e-12);
  EXPECT_NEAR(std::sqrt(fused.covariance(0, 0)), 0.02 * 0.04 / std::hypot(0.02, 0.04), 1e-12);
  const double yaw_weight = 1e-6 / (1e-6 + 1e-2);
  EXPECT_NEAR(poseError(a.pose, fused.pose)(5), yaw_weight * 0.01, 1e-12);
  EXPECT_TRUE(fusePoses(b, a).pose.isApprox(fused.pose, 1e-9));
}

// Carried along an exact motion, the covariance is that of the errors it
// predicts: 20000 poses drawn from Sigma_a (5 cm, 0.6 degrees) and moved 10 m,
// where the rotation error alone moves the end 10 cm; every entry of the
// sample covariance of their errors at the end lies within 4 standard errors
// (sqrt(2 / N) of sqrt(Sigma_ii Sigma_jj)) of Sigma_b's.
TEST(Pose, ComposingAnExactMotionCarriesTheCovarianceItPredicts) {
  PoseWithCovariance T_world_a;
  T_world_a.pose = makePose(
      {3.0, -1.0, 1.5},
      Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, -0.3, 1.0).normalized())));
  T_world_a.covariance = diagonalPoseCovariance(0.05, 0.01);
  T_world_a.covariance(0, 4) = T_world_a.covariance(4, 0) = 0.5 * 0.05 * 0.01;
  const Eigen::Isometry3d T_a_b = makePose(
      {0.5, -0.3, 10.0}, Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY())));
  const PoseWithCovariance T_world_b = composeExactMotion(T_world_a, T_a_b);
  EXPECT_TRUE(T_world_b.pose.isApprox(T_world_a.pose * T_a_b, 1e-12));

  constexpr int kSamples = 20000;
  const Matrix6d root = T_world_a.covariance.llt().matrixL();
  std::mt19937 random(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  Matrix6d sample_covariance = Matrix6d::Zero();
  for (int i = 0; i < kSamples; ++i) {
    Eigen::Matrix<double, 6, 1> draw;
    for (int k = 0; k < 6; ++k) {
      draw[k] = normal(random);
    }
    const Eigen::Isometry3d true_a = applyPoseError(T_world_a.pose, root * draw);
    const Eigen::Matrix<double, 6, 1> error_b = poseError(T_world_b.pose, true_a * T_a_b);
    sample_covariance += error_b * error_b.transpose() / kSamples;
  }
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 6; ++col) {
      const double scale =
          std::sqrt(T_world_b.covariance(row, row) * T_world_b.covariance(col, col));
      EXPECT_NEAR(sample_covariance(row, col), T_world_b.covariance(row, col),
                  4.0 * std::sqrt(2.0 / kSamples) * scale)
          << row << ", " << col;
    }
  }
}

// With a diagonal covariance the NEES is the sum of squared errors in sigmas.
// A pose and its truth carried into another world frame, or into a scaled
// world, keep their error in the estimate's covariance: the normalized error
// is invariant, for errors along every axis of a correlated covariance.
TEST(Pose, AChangeOfWorldFrameOrScaleKeepsTheErrorInItsCovariance) {
  const Eigen::Isometry3d estimate = makePose(
      {4.0, -2.0, 1.5}, Eigen::Quaterniond(Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitZ())));
  Eigen::Matrix<double, 6, 6> root = Eigen::Matrix<double, 6, 6>::Identity() * 0.02;
  root(0, 4) = 0.01;
  root(5, 1) = 0.004;
  const PoseWithCovariance T_a_c{estimate, root * root.transpose()};
  const Eigen::Isometry3d T_b_a =
      makePose({10.0, 0.5, -3.0},
               Eigen::Quaterniond(Eigen::AngleAxisd(-M_PI / 2.0, Eigen::Vector3d::UnitX())));
  for (int axis = 0; axis < 6; ++axis) {
    Eigen::Matrix<double, 6, 1> error = Eigen::Matrix<double, 6, 1>::Zero();
    error(axis) = 0.01;
    const Eigen::Isometry3d truth = applyPoseError(estimate, error);
    const double nees = normalizedErrorSquared(T_a_c, truth);
    EXPECT_NEAR(normalizedErrorSquared(changeWorldFrame(T_b_a, T_a_c), T_b_a * truth), nees,
                1e-6 * nees)
        << axis;
    Eigen::Isometry3d truth_scaled = truth;
    truth_scaled.translation() *= 0.05;
    EXPECT_NEAR(normalizedErrorSquared(scaledWorld(T_a_c, 0.05), truth_scaled), nees, 1e-6 * nees)
        << axis;
  }
  const PoseWithCovariance turned = changeWorldFrame(T_b_a, T_a_c);
  EXPECT_TRUE(turned.pose.isApprox(T_b_a * estimate));
  const PoseWithCovariance scaled = scaledWorld(T_a_c, 0.05);
  EXPECT_TRUE(scaled.pose.translation().isApprox(0.05 * estimate.translation()));
  EXPECT_TRUE(scaled.pose.linear().isApprox(estimate.linear()));
  EXPECT_NEAR(scaled.covariance(5, 5), T_a_c.covariance(5, 5), 1e-18);
  EXPECT_NEAR(scaled.covariance(0, 0), 0.0025 * T_a_c.covariance(0, 0), 1e-18);
}

TEST(Pose, NormalizedErrorIsTheErrorInItsOwnSigmas) {
  PoseWithCovariance estimate;
  estimate.covariance = diagonalPoseCovariance(0.02, 0.001);
  Eigen::Isometry3d truth = estimate.pose;
  truth.translation() = Eigen::Vector3d(0.04, 0.0, -0.02);  // 2 and 1 sigma
  truth.linear() = Eigen::AngleAxisd(0.003, Eigen::Vector3d::UnitZ()).toRotationMatrix();  // 3
  EXPECT_NEAR(normalizedErrorSquared(estimate, truth), 4.0 + 1.0 + 9.0, 1e-9);
}

// A 3 cm by 12 cm ellipse turned 30 degrees about the vertical: its long axis,
// whatever the rotation and attitude entries.
TEST(Pose, LargestPositionSigmaIsAlongTheLongestPrincipalAxis) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.5236, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Matrix6d covariance = diagonalPoseCovariance(0.0, 0.01);
  covariance.topLeftCorner<3, 3>() =
      R * Eigen::Vector3d(0.03 * 0.03, 0.12 * 0.12, 0.02 * 0.02).asDiagonal() * R.transpose();
  EXPECT_NEAR(largestPositionSigma(covariance), 0.12, 1e-12);
}

TEST(CoveringCovariance, IsTheFirstWhereItCoversTheSecond) {
  const Matrix6d covariance = diagonalPoseCovariance(0.1, 0.01);
  const Matrix6d covering = coveringCovariance(covariance, 0.5 * covariance);
  EXPECT_LT((covering - covariance).norm(), 1e-12);
}

TEST(CoveringCovariance, GrowsOnlyTheDirectionsWhereTheSecondIsLarger) {
  const Matrix6d covariance = diagonalPoseCovariance(0.1, 0.01);
  Eigen::Matrix<double, 6, 1> along_x_and_yaw = Eigen::Matrix<double, 6, 1>::Zero();
  along_x_and_yaw(0) = 0.3;
  along_x_and_yaw(5) = 0.02;
  const Matrix6d larger_there = along_x_and_yaw * along_x_and_yaw.transpose();
  const Matrix6d covering = coveringCovariance(covariance, larger_there);
  // Along the second's one direction it takes over: v^T Sigma'^-1 v = 1
  // for v that direction scaled by its sigma.
  EXPECT_NEAR(along_x_and_yaw.dot(covering.ldlt().solve(along_x_and_yaw)), 1.0, 1e-9);
  // Perpendicular to it, in that metric, nothing changes.
  EXPECT_NEAR(covering(1, 1), covariance(1, 1), 1e-12);
  EXPECT_NEAR(covering(2, 2), covariance(2, 2), 1e-12);
  EXPECT_NEAR(covering(3, 3), covariance(3, 3), 1e-12);
}

TEST(CoveringCovariance, IsInfiniteForACovarianceThatIsNotPositiveDefinite) {
  Matrix6d singular = diagonalPoseCovariance(0.1, 0.01);
  singular(2, 2) = 0.0;
  EXPECT_FALSE(coveringCovariance(singular, Matrix6d::Identity()).allFinite());
}

TEST(RigidTransform, AMatrixOfTheWrongSizeNamesItsSource) {
  try {
    rigidTransform({1, 0, 0, 0}, "T_body_camera");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("T_body_camera: a rigid transform is 16 numbers"),
              std::string::npos)
        << error.what();
  }
}

TEST(RigidTransform, ReadsARowMajorMatrix) {
  const Eigen::Isometry3d T =
      rigidTransform({0, -1, 0, 1.5, 1, 0, 0, -2, 0, 0, 1, 0.25, 0, 0, 0, 1}, "T");
  EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(1.5, -2.0, 0.25)));
  EXPECT_TRUE((T.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
}

}  // namespace
}  // namespace lineloc
