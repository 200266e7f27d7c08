// The filter's updates: a vision fix updates with R - U, inflated for a fix
// of an unchanged view; DGPS positions and compass readings bound the
// estimate at their own sigma and are skipped once it is better; a DGPS
// velocity makes the velocity known; zero-velocity updates only when the IMU
// is still, the speed small, the velocity known and the last one old enough.
#include "robot/inertial/navigation_filter.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/stats/chi_square.h"
#include "robot/inertial/measurement_models.h"

namespace lineloc {
namespace {

constexpr double kDeg = M_PI / 180.0;

FilterSnapshot snapshotWithSigmas(double position_sigma_m, double velocity_sigma_mps,
                                  double yaw_sigma_rad) {
  FilterSnapshot snapshot;
  snapshot.state.stamp_ns = 1'000'000'000;
  snapshot.state.p_world_body = Eigen::Vector3d(10.0, 20.0, 1.0);
  snapshot.state.q_world_body =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  snapshot.imu.stamp_ns = snapshot.state.stamp_ns;
  ErrorVector sigma;
  sigma << Eigen::Vector3d::Constant(position_sigma_m),
      Eigen::Vector3d::Constant(velocity_sigma_mps), 0.01, 0.01, yaw_sigma_rad,
      Eigen::Vector3d::Constant(0.0035), Eigen::Vector3d::Constant(0.05);
  snapshot.covariance = sigma.cwiseAbs2().asDiagonal();
  return snapshot;
}

TEST(NavigationFilter, AVisionFixUpdatesWithItsCovarianceLessTheUnprovenPart) {
  const InertialNavigatorConfig config;
  const NavigationFilter filter(config);
  FilterSnapshot snapshot = snapshotWithSigmas(0.5, 0.1, 2.0 * kDeg);
  snapshot.position_known = false;
  snapshot.velocity_known = false;
  VisionPayload fix;
  fix.T_world_camera = cameraPoseOf(snapshot.state, snapshot.covariance, config.T_body_camera);
  fix.T_world_camera.pose.translation() += Eigen::Vector3d(0.1, -0.05, 0.0);
  fix.T_world_camera.covariance = diagonalPoseCovariance(0.05, 0.2 * kDeg);
  fix.unproven_covariance = levelFrameOffset(diagonalPoseCovariance(0.03, 0.1 * kDeg));
  const double gate = chiSquareQuantile(config.gate_probability, 6.0);

  const auto expectUpdate = [&](double inflation) {
    NavigationState expected_state = snapshot.state;
    ErrorCovariance expected_covariance = snapshot.covariance;
    const LinearisedMeasurement<6> z =
        linearisePoseFix(expected_state, fix.T_world_camera, config.T_body_camera);
    ASSERT_EQ(
        applyUpdate(z, gate, expected_state, expected_covariance,
                    Matrix6d(inflation * (fix.T_world_camera.covariance - fix.unproven_covariance)))
            .status,
        UpdateStatus::kAccepted);
    Measurement measurement(fix);
    ASSERT_EQ(filter.apply(measurement, snapshot.imu, snapshot), MeasurementOutcome::kAccepted);
    EXPECT_EQ(*measurement.vision_residual, z.residual);
    EXPECT_EQ(snapshot.state.p_world_body, expected_state.p_world_body);
    EXPECT_EQ(snapshot.covariance, expected_covariance);
  };
  // The first fix counts in full; the next, of the same view from the state
  // it left, once in ten thousand.
  expectUpdate(1.0);
  EXPECT_TRUE(snapshot.position_known);
  EXPECT_TRUE(snapshot.velocity_known);
  ASSERT_TRUE(snapshot.fixes.at_last_fix);
  EXPECT_EQ(snapshot.fixes.at_last_fix->p_world_body, snapshot.state.p_world_body);
  expectUpdate(CorrelatedFixModel::kMaxInflation);

  Measurement far(fix);
  std::get<VisionPayload>(far.payload).T_world_camera.pose.translation().x() += 3.0;
  EXPECT_EQ(filter.apply(far, snapshot.imu, snapshot), MeasurementOutcome::kGated);
  EXPECT_TRUE(far.vision_residual);
}

// DGPS errors are correlated over minutes: a fix bounds the horizontal
// position at its 5 m, the next adds nothing, and one to a position tracked
// to centimetres is skipped.
TEST(NavigationFilter, ADgpsFixBoundsThePositionAtItsOwnSigma) {
  const InertialNavigatorConfig config;
  const NavigationFilter filter(config);
  FilterSnapshot snapshot = snapshotWithSigmas(20.0, 0.1, 2.0 * kDeg);
  snapshot.position_known = false;
  const Eigen::Matrix3d five_by_ten = Eigen::Vector3d(25.0, 25.0, 100.0).asDiagonal();
  Measurement fix(GpsPayload{snapshot.state.p_world_body, five_by_ten});
  EXPECT_EQ(filter.apply(fix, snapshot.imu, snapshot), MeasurementOutcome::kAccepted);
  EXPECT_TRUE(snapshot.position_known);
  EXPECT_NEAR(std::sqrt(snapshot.covariance(kPosition, kPosition)), 5.0, 1e-9);
  EXPECT_NEAR(std::sqrt(snapshot.covariance(kPosition + 2, kPosition + 2)), 10.0, 1e-9);
  filter.apply(fix, snapshot.imu, snapshot);
  EXPECT_NEAR(std::sqrt(snapshot.covariance(kPosition, kPosition)), 5.0, 1e-9);
  FilterSnapshot tracked = snapshotWithSigmas(0.5, 0.1, 2.0 * kDeg);
  EXPECT_EQ(filter.apply(fix, tracked.imu, tracked), MeasurementOutcome::kSkipped);
  Measurement far(
      GpsPayload{snapshot.state.p_world_body + Eigen::Vector3d(100.0, 0.0, 0.0), five_by_ten});
  EXPECT_EQ(filter.apply(far, snapshot.imu, snapshot), MeasurementOutcome::kGated);
}

// A compass reading bounds the yaw at sigma_c = hypot(white, shared), and
// records its residual against the filter's heading; to a yaw known better
// it adds nothing.
TEST(NavigationFilter, ACompassReadingBoundsTheYawAtOneReadingsSigma) {
  const InertialNavigatorConfig config;
  const NavigationFilter filter(config);
  FilterSnapshot snapshot = snapshotWithSigmas(0.5, 0.1, 30.0 * kDeg);
  Measurement reading(YawPayload{0.3 + 0.1});
  EXPECT_EQ(filter.apply(reading, snapshot.imu, snapshot), MeasurementOutcome::kAccepted);
  EXPECT_NEAR(*reading.yaw_residual_rad, 0.1, 1e-12);
  EXPECT_NEAR(std::sqrt(snapshot.covariance(kAttitude + 2, kAttitude + 2)),
              compassYawSigma_rad(config), 1e-9);
  FilterSnapshot tracked = snapshotWithSigmas(0.5, 0.1, 1.0 * kDeg);
  EXPECT_EQ(filter.apply(reading, tracked.imu, tracked), MeasurementOutcome::kSkipped);
}

TEST(NavigationFilter, ADgpsVelocityMakesTheVelocityKnown) {
  const NavigationFilter filter{InertialNavigatorConfig{}};
  FilterSnapshot snapshot = snapshotWithSigmas(0.5, 3.0, 2.0 * kDeg);
  snapshot.velocity_known = false;
  Measurement velocity(GpsVelocityPayload{Eigen::Vector2d(1.0, 0.5)});
  EXPECT_EQ(filter.apply(velocity, snapshot.imu, snapshot), MeasurementOutcome::kAccepted);
  EXPECT_TRUE(snapshot.velocity_known);
  EXPECT_LT(snapshot.covariance(kVelocity, kVelocity), 0.1 * 0.1);
}

TEST(NavigationFilter, ZeroVelocityUpdatesWhenStillSlowKnownAndDue) {
  const InertialNavigatorConfig config;
  const NavigationFilter filter(config);
  FilterSnapshot slow = snapshotWithSigmas(0.5, 0.1, 2.0 * kDeg);
  slow.state.v_world_body = Eigen::Vector3d(0.05, 0.0, 0.0);
  slow.last_zero_velocity_ns = 900'000'000;
  const ImuSample at{slow.state.stamp_ns, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};

  FilterSnapshot updated = slow;
  filter.updateZeroVelocity(at, true, updated);
  EXPECT_EQ(updated.zero_velocity_updates, 1);
  EXPECT_EQ(updated.last_zero_velocity_ns, at.stamp_ns);
  EXPECT_LT(updated.state.v_world_body.norm(), 0.05);
  // The next one is not due before zero_velocity_interval_ns.
  ImuSample soon = at;
  soon.stamp_ns += config.zero_velocity_interval_ns - 1;
  filter.updateZeroVelocity(soon, true, updated);
  EXPECT_EQ(updated.zero_velocity_updates, 1);

  const auto updates = [&](FilterSnapshot snapshot, bool still) {
    filter.updateZeroVelocity(at, still, snapshot);
    return snapshot.zero_velocity_updates;
  };
  EXPECT_EQ(updates(slow, false), 0);
  FilterSnapshot fast = slow;
  fast.state.v_world_body.x() = config.zero_velocity_max_speed_mps;
  EXPECT_EQ(updates(fast, true), 0);
  FilterSnapshot unknown = slow;
  unknown.velocity_known = false;
  EXPECT_EQ(updates(unknown, true), 0);
}

}  // namespace
}  // namespace lineloc
