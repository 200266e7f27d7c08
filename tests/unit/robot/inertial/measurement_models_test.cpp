#include "robot/inertial/measurement_models.h"

#include <gtest/gtest.h>

#include <functional>

#include "robot/inertial/inertial_navigator.h"

namespace lineloc {
namespace {

NavigationState tiltedState() {
  NavigationState state;
  state.p_world_body = Eigen::Vector3d(10.0, 5.0, 1.0);
  state.v_world_body = Eigen::Vector3d(1.0, -0.5, 0.1);
  state.q_world_body = expSO3(Eigen::Vector3d(0.1, -0.2, 2.5));
  return state;
}

// Checks H against central differences of the residual, r(x + dx) = r(x) - H dx
// to first order. Central differences with h = 1e-6 are exact to O(h^2); the
// models linearise Log() at a zero residual, which costs |r| / 2 relative, so
// measurements are built within 1e-5 of the prediction and the tolerance is 1e-5.
template <int M>
void expectJacobianMatchesNumerical(
    const std::function<LinearisedMeasurement<M>(const NavigationState&)>& linearise) {
  const NavigationState state = tiltedState();
  const LinearisedMeasurement<M> z = linearise(state);
  constexpr double h = 1e-6;
  for (int i = 0; i < kErrorStateSize; ++i) {
    ErrorVector dx = ErrorVector::Zero();
    dx(i) = h;
    NavigationState plus = state;
    NavigationState minus = state;
    injectError(dx, plus);
    injectError(-dx, minus);
    const Eigen::Matrix<double, M, 1> numerical =
        -(linearise(plus).residual - linearise(minus).residual) / (2 * h);
    EXPECT_LT((numerical - z.jacobian.col(i)).norm(), 1e-5) << "column " << i;
  }
}

TEST(MeasurementModels, PoseFixJacobian) {
  Eigen::Isometry3d T_body_camera = InertialNavigatorConfig::defaultBodyCamera();
  T_body_camera.translation() = Eigen::Vector3d(0.3, -0.1, 0.8);
  const NavigationState state = tiltedState();
  PoseWithCovariance fix = cameraPoseOf(state, ErrorCovariance::Identity(), T_body_camera);
  fix.pose.translation() += Eigen::Vector3d(3e-6, -2e-6, 1e-6);
  fix.pose.linear() =
      expSO3(Eigen::Vector3d(4e-6, 1e-6, -5e-6)).toRotationMatrix() * fix.pose.linear();
  expectJacobianMatchesNumerical<6>(
      [&](const NavigationState& s) { return linearisePoseFix(s, fix, T_body_camera); });
  EXPECT_LT(linearisePoseFix(state, fix, T_body_camera).residual.norm(), 1e-5);
}

TEST(MeasurementModels, AntennaPositionJacobian) {
  const Eigen::Vector3d lever_arm(-0.4, 0.2, 1.1);
  expectJacobianMatchesNumerical<3>([&](const NavigationState& s) {
    return lineariseAntennaPosition(s, Eigen::Vector3d(11.0, 4.0, 2.0), Eigen::Matrix3d::Identity(),
                                    lever_arm);
  });
}

TEST(MeasurementModels, AntennaVelocityJacobianAndLeverArm) {
  const Eigen::Vector3d lever_arm(-0.4, 0.2, 1.1);
  const Eigen::Vector3d gyro_radps(0.05, -0.1, 0.6);
  expectJacobianMatchesNumerical<2>([&](const NavigationState& s) {
    return lineariseAntennaVelocity(s, gyro_radps, Eigen::Vector2d(1.2, -0.3), 0.1, lever_arm);
  });
  // Turning on the spot at 0.6 rad/s, an antenna 1 m ahead of the body's
  // origin moves 0.6 m/s sideways.
  NavigationState turning;
  turning.q_world_body = expSO3(Eigen::Vector3d(0.0, 0.0, M_PI_2));
  const LinearisedMeasurement<2> z =
      lineariseAntennaVelocity(turning, Eigen::Vector3d(0.0, 0.0, 0.6), Eigen::Vector2d::Zero(),
                               0.1, Eigen::Vector3d::UnitX());
  EXPECT_NEAR(z.residual.x(), 0.6, 1e-12);
  EXPECT_NEAR(z.residual.y(), 0.0, 1e-12);
  EXPECT_NEAR(z.noise(0, 0), 0.01, 1e-15);
}

TEST(MeasurementModels, YawJacobianAndWrap) {
  const double yaw = yawOf(tiltedState().q_world_body);
  expectJacobianMatchesNumerical<1>(
      [&](const NavigationState& s) { return *lineariseYaw(s, yaw + 1e-6, 0.01); });
  // Residuals wrap: measuring yaw + 2 pi - 0.1 is a residual of -0.1.
  EXPECT_NEAR(lineariseYaw(tiltedState(), yaw + 2 * M_PI - 0.1, 0.01)->residual(0), -0.1, 1e-12);
  NavigationState pointing_up;
  pointing_up.q_world_body = expSO3(Eigen::Vector3d(0.0, -M_PI_2, 0.0));
  EXPECT_FALSE(lineariseYaw(pointing_up, 0.0, 0.01).has_value());
}

TEST(MeasurementModels, ZeroVelocityJacobian) {
  expectJacobianMatchesNumerical<3>(
      [](const NavigationState& s) { return lineariseZeroVelocity(s, 0.01); });
}

TEST(MeasurementModels, CameraPoseCovarianceIsTheLeverArmTransform) {
  Eigen::Isometry3d T_body_camera = InertialNavigatorConfig::defaultBodyCamera();
  T_body_camera.translation() = Eigen::Vector3d(0.5, 0.0, 0.0);
  ErrorCovariance P = ErrorCovariance::Zero();
  P(kAttitude + 2, kAttitude + 2) = 1e-4;  // yaw only: sigma 0.01 rad
  NavigationState state;
  const PoseWithCovariance camera = cameraPoseOf(state, P, T_body_camera);
  // A yaw error of 0.01 rad swings a camera 0.5 m ahead sideways by 5 mm.
  EXPECT_NEAR(std::sqrt(camera.covariance(1, 1)), 0.005, 1e-12);
  EXPECT_NEAR(camera.covariance(0, 0), 0.0, 1e-15);
  EXPECT_NEAR(camera.covariance(5, 5), 1e-4, 1e-15);
  EXPECT_TRUE(camera.pose.translation().isApprox(Eigen::Vector3d(0.5, 0.0, 0.0)));
}

TEST(MeasurementModels, WrapAngle) {
  EXPECT_DOUBLE_EQ(wrapAngle(M_PI), M_PI);
  EXPECT_DOUBLE_EQ(wrapAngle(-M_PI), M_PI);
  EXPECT_NEAR(wrapAngle(3 * M_PI + 0.5), -M_PI + 0.5, 1e-12);
}

// An update with its own noise R_u equals one whose R is R_u; its gate is the
// one of R.
TEST(ErrorStateUpdate, UpdatesWithItsUpdateNoiseAndGatesWithR) {
  LinearisedMeasurement<3> z;
  z.jacobian.block<3, 3>(0, kPosition).setIdentity();
  z.noise = 0.01 * Eigen::Matrix3d::Identity();
  z.residual = Eigen::Vector3d(0.1, -0.05, 0.02);
  const ErrorCovariance prior = 0.04 * ErrorCovariance::Identity();
  for (const double update_scale : {4.0, 0.25}) {
    const Eigen::Matrix3d update_noise = update_scale * z.noise;
    NavigationState updated_state;
    ErrorCovariance updated = prior;
    ASSERT_EQ(applyUpdate(z, 100.0, updated_state, updated, update_noise).status,
              UpdateStatus::kAccepted);
    LinearisedMeasurement<3> as_noise = z;
    as_noise.noise = update_noise;
    NavigationState expected_state;
    ErrorCovariance expected = prior;
    ASSERT_EQ(applyUpdate(as_noise, 100.0, expected_state, expected).status,
              UpdateStatus::kAccepted);
    EXPECT_TRUE(updated.isApprox(expected, 1e-12)) << update_scale;
    EXPECT_TRUE(updated_state.p_world_body.isApprox(expected_state.p_world_body, 1e-12));
  }

  // NIS 0.258 with R (S = 0.05 I), whatever R_u (0.161 with 4 R, 0.36 with
  // R / 4): gated at 0.2, passed at 0.3.
  for (const auto& [update_scale, gate] : {std::pair{4.0, 0.2}, std::pair{0.25, 0.2}}) {
    NavigationState state;
    ErrorCovariance covariance = prior;
    EXPECT_EQ(
        applyUpdate(z, gate, state, covariance, Eigen::Matrix3d(update_scale * z.noise)).status,
        UpdateStatus::kGated);
  }
  NavigationState state;
  ErrorCovariance covariance = prior;
  EXPECT_EQ(applyUpdate(z, 0.3, state, covariance, Eigen::Matrix3d(0.25 * z.noise)).status,
            UpdateStatus::kAccepted);
}

}  // namespace
}  // namespace lineloc
