// The vision fixes' correlated error against its formulas: the inflation
// (1 + rho) / (1 - rho) with rho = exp(-(|dp| / L_p + |dtheta| / L_theta)),
// the covariance the travel d decorrelates, (rho_s^2(d_0) - rho_s^2(d_1)) S,
// the shared error an applied fix leaves, S = (1 - w) S + w f (R - U) level,
// and the covariance reported, covering both P + U and f R.
#include "robot/inertial/correlated_fix_model.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

namespace lineloc {
namespace {

constexpr double kDeg = M_PI / 180.0;

// A camera mounted at the body's origin and axes: a fix's body covariance is its own.
InertialNavigatorConfig cameraAtBody() {
  InertialNavigatorConfig config;
  config.T_body_camera = Eigen::Isometry3d::Identity();
  return config;
}

NavigationState stateAt(const Eigen::Vector3d& p_world_body, double yaw_rad = 0.0) {
  NavigationState state;
  state.p_world_body = p_world_body;
  state.q_world_body = Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()));
  return state;
}

VisionPayload fixWith(const Matrix6d& covariance, const Matrix6d& unproven) {
  VisionPayload fix;
  fix.T_world_camera.pose = Eigen::Isometry3d::Identity();
  fix.T_world_camera.covariance = covariance;
  fix.unproven_covariance = unproven;
  return fix;
}

bool isPositiveSemiDefinite(const Matrix6d& m) {
  return Eigen::SelfAdjointEigenSolver<Matrix6d>(m).eigenvalues().minCoeff() > -1e-15;
}

TEST(CorrelatedFixModel, InflationIsOneBeforeAnyFixAndForIndependentFixes) {
  const InertialNavigatorConfig config;
  const CorrelatedFixModel model(config);
  EXPECT_EQ(model.inflation(stateAt(Eigen::Vector3d::Zero()), FixCorrelation{}), 1.0);

  InertialNavigatorConfig independent = config;
  independent.vision_error_correlation_m = 0.0;
  FixCorrelation last;
  last.at_last_fix = stateAt(Eigen::Vector3d::Zero());
  EXPECT_EQ(CorrelatedFixModel(independent).inflation(stateAt(Eigen::Vector3d::Zero()), last), 1.0);
}

TEST(CorrelatedFixModel, InflatesByTheGaussMarkovCorrelationOfTheCameraMotion) {
  InertialNavigatorConfig config;
  config.vision_error_correlation_m = 0.02;
  config.vision_error_correlation_rad = 0.2 * kDeg;
  const CorrelatedFixModel model(config);
  FixCorrelation last;
  last.at_last_fix = stateAt(Eigen::Vector3d(1.0, 2.0, 0.0), 0.3);
  const Eigen::Vector3d dp(0.012, -0.016, 0.0);  // 2 cm
  const double dtheta = 0.1 * kDeg;
  const NavigationState moved = stateAt(Eigen::Vector3d(1.0, 2.0, 0.0) + dp, 0.3 + dtheta);
  const double rho = std::exp(-(0.02 / 0.02 + dtheta / (0.2 * kDeg)));  // e^-1.5
  EXPECT_NEAR(model.inflation(moved, last), (1.0 + rho) / (1.0 - rho), 1e-9);
  EXPECT_NEAR(model.inflation(moved, last), 1.5744, 1e-4);

  // A standing robot's next fix, of the same view, counts once: bounded.
  EXPECT_EQ(model.inflation(*last.at_last_fix, last), CorrelatedFixModel::kMaxInflation);
  // Far from the last fix, nearly independent.
  EXPECT_NEAR(model.inflation(stateAt(Eigen::Vector3d(2.0, 2.0, 0.0), 0.3), last), 1.0, 1e-12);
}

TEST(CorrelatedFixModel, ForgetsTheSharedErrorTheTravelDecorrelates) {
  InertialNavigatorConfig config = cameraAtBody();
  config.shared_fix_error_length_m = 2.5;
  const CorrelatedFixModel model(config);
  FixCorrelation last;
  last.at_last_fix = stateAt(Eigen::Vector3d::Zero());
  last.shared_fix_error = diagonalPoseCovariance(0.1, 0.01);
  ErrorCovariance covariance = ErrorCovariance::Identity() * 1e-4;
  const ErrorCovariance before = covariance;
  model.forget(Eigen::Vector3d(1.0, 0.0, 0.0), Eigen::Vector3d(1.5, 0.0, 0.0), last, covariance);
  const double decorrelated = std::exp(-2.0 * 1.0 / 2.5) - std::exp(-2.0 * 1.5 / 2.5);
  ErrorCovariance grown = before;
  setPoseBlock(poseBlock(before) + decorrelated * last.shared_fix_error, grown);
  EXPECT_TRUE(covariance.isApprox(grown, 1e-12));
  EXPECT_GT(covariance(0, 0), before(0, 0));

  // Travel back towards the fix restores nothing; without L_s nothing is forgotten.
  const ErrorCovariance forgotten = covariance;
  model.forget(Eigen::Vector3d(1.5, 0.0, 0.0), Eigen::Vector3d(1.0, 0.0, 0.0), last, covariance);
  EXPECT_EQ(covariance, forgotten);
  CorrelatedFixModel(cameraAtBody())
      .forget(Eigen::Vector3d::Zero(), Eigen::Vector3d(10.0, 0.0, 0.0), last, covariance);
  EXPECT_EQ(covariance, forgotten);
}

TEST(CorrelatedFixModel, AnAppliedFixLeavesItsShareOfTheSharedError) {
  InertialNavigatorConfig config = cameraAtBody();
  config.shared_fix_error_fraction = 0.5;
  const CorrelatedFixModel model(config);
  const Matrix6d R = diagonalPoseCovariance(0.04, 0.2 * kDeg);
  const Matrix6d U = levelFrameOffset(diagonalPoseCovariance(0.02, 0.1 * kDeg));
  const VisionPayload fix = fixWith(R, U);
  const NavigationState state = stateAt(Eigen::Vector3d(3.0, 4.0, 0.0));
  // The update took the position variance from a trace of 1 to 0.25: w = 0.75.
  ErrorCovariance covariance = ErrorCovariance::Identity();
  covariance.block<3, 3>(kPosition, kPosition) = Eigen::Matrix3d::Identity() * 0.25 / 3.0;
  FixCorrelation last;
  model.recordApplied(fix, state, 1.0, covariance, last);
  ASSERT_TRUE(last.at_last_fix);
  EXPECT_EQ(last.at_last_fix->p_world_body, state.p_world_body);
  EXPECT_TRUE(last.unproven_covariance.isApprox(U, 1e-12));
  EXPECT_TRUE(last.fix_offset_covariance.isApprox(0.5 * R, 1e-12));
  const Matrix6d level_shared = levelFrameOffset(R - U);
  EXPECT_TRUE(last.shared_fix_error.isApprox(0.75 * 0.5 * level_shared, 1e-12));

  // The next fix takes a tenth: S = 0.9 S + 0.1 f (R - U).
  const Matrix6d S = last.shared_fix_error;
  model.recordApplied(fix, state, 1.0, ErrorCovariance::Identity() * 0.9 / 3.0, last);
  EXPECT_TRUE(last.shared_fix_error.isApprox(0.9 * S + 0.1 * 0.5 * level_shared, 1e-12));
  // A fix that took nothing out of a singular position block leaves S alone.
  model.recordApplied(fix, state, 0.0, ErrorCovariance::Zero(), last);
  EXPECT_TRUE(last.shared_fix_error.isApprox(0.9 * S + 0.1 * 0.5 * level_shared, 1e-12));
}

TEST(CorrelatedFixModel, LevelFrameOffsetKeepsAllButTheTilt) {
  Matrix6d covariance = Matrix6d::Constant(0.1) + Matrix6d::Identity();
  const Matrix6d level = levelFrameOffset(covariance);
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      const bool tilt = i == 3 || i == 4 || j == 3 || j == 4;
      EXPECT_EQ(level(i, j), tilt ? 0.0 : covariance(i, j)) << i << ", " << j;
    }
  }
}

TEST(CorrelatedFixModel, ReportsTheUnprovenOffsetAndTheSharedFloor) {
  const CorrelatedFixModel model(cameraAtBody());
  ErrorCovariance covariance = ErrorCovariance::Identity() * 1e-4;
  covariance(kVelocity, kVelocity) = 0.3;
  FixCorrelation last;
  last.unproven_covariance = levelFrameOffset(diagonalPoseCovariance(0.15, 0.3 * kDeg));
  last.fix_offset_covariance = diagonalPoseCovariance(0.1, 1.0 * kDeg);
  const ErrorCovariance reported = model.reported(covariance, last);
  const Matrix6d pose = poseBlock(reported);
  EXPECT_TRUE(isPositiveSemiDefinite(pose - poseBlock(covariance) - last.unproven_covariance));
  EXPECT_TRUE(isPositiveSemiDefinite(pose - last.fix_offset_covariance));
  // Diagonal: the larger of the two, axis by axis.
  EXPECT_NEAR(pose(0, 0), 1e-4 + 0.15 * 0.15, 1e-12);
  EXPECT_NEAR(pose(3, 3), 1.0 * kDeg * 1.0 * kDeg, 1e-12);
  EXPECT_EQ(reported(kVelocity, kVelocity), 0.3);

  // An exactly known state is reported as uncertain by f R alone.
  FixCorrelation floor_only;
  floor_only.fix_offset_covariance = last.fix_offset_covariance;
  EXPECT_TRUE(poseBlock(model.reported(ErrorCovariance::Zero(), floor_only))
                  .isApprox(floor_only.fix_offset_covariance, 1e-12));
}

}  // namespace
}  // namespace lineloc
