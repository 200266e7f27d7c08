#include <gtest/gtest.h>

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
  Eigen::Isometry3d truth = estimate;
  truth.translation() += error.head<3>();
  truth.linear() =
      Eigen::AngleAxisd(error.tail<3>().norm(), error.tail<3>().normalized()) * estimate.linear();
  EXPECT_TRUE(poseError(estimate, truth).isApprox(error, 1e-12));
}

// With a diagonal covariance the NEES is the sum of squared errors in sigmas.
TEST(Pose, NormalizedErrorIsTheErrorInItsOwnSigmas) {
  PoseWithCovariance estimate;
  estimate.covariance = diagonalPoseCovariance(0.02, 0.001);
  Eigen::Isometry3d truth = estimate.pose;
  truth.translation() = Eigen::Vector3d(0.04, 0.0, -0.02);  // 2 and 1 sigma
  truth.linear() = Eigen::AngleAxisd(0.003, Eigen::Vector3d::UnitZ()).toRotationMatrix();  // 3
  EXPECT_NEAR(normalizedErrorSquared(estimate, truth), 4.0 + 1.0 + 9.0, 1e-9);
}

}  // namespace
}  // namespace lineloc
