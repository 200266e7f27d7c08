// The starts before the filter runs, on made-up readings whose start is known:
// standing (roll, pitch and gyro bias from the still window, yaw from the
// compass, position from DGPS, each with the sigma the header states), in
// motion from two DGPS velocities, and from vision fixes; and the DGPS
// velocities that hold or bar the standing start.
#include "robot/inertial/startup_alignment.h"

#include <gtest/gtest.h>

#include <cmath>

#include "robot/inertial/measurement_models.h"

namespace lineloc {
namespace {

constexpr int64_t kSamplePeriod_ns = 5'000'000;  // 200 Hz
constexpr double kG = 9.80665;
constexpr double kRoll = 0.02;
constexpr double kPitch = -0.01;
constexpr double kYaw = 0.7;
const Eigen::Vector3d kStandingGyroBias_radps(1e-3, -2e-3, 5e-4);

// A robot and its sensors before the start.
struct Bench {
  explicit Bench(const InertialNavigatorConfig& config_in = {})
      : config(config_in), filter(config), history(config.history_ns), startup(config) {}

  void addImu(const ImuSample& sample) {
    history.addImu({sample, false}, filter);
    startup.addImu(sample);
  }
  // Standing at kRoll and kPitch with the gyros kStandingGyroBias_radps off, [from_ns, to_ns].
  void stand(int64_t from_ns, int64_t to_ns) {
    const Eigen::Vector3d f_body(-kG * std::sin(kPitch), kG * std::cos(kPitch) * std::sin(kRoll),
                                 kG * std::cos(kPitch) * std::cos(kRoll));
    for (int64_t t = from_ns; t <= to_ns; t += kSamplePeriod_ns) {
      addImu({t, kStandingGyroBias_radps, f_body});
    }
  }
  // Compass yaws at 10 Hz over [from_ns, to_ns].
  void compass(int64_t from_ns, int64_t to_ns, double yaw_rad) {
    for (int64_t t = from_ns; t <= to_ns; t += 100'000'000) {
      startup.addCompassYaw({t, yaw_rad});
    }
  }

  InertialNavigatorConfig config;
  NavigationFilter filter;
  MeasurementHistory history;
  StartupAlignment startup;
};

ErrorVector sigmasOf(const ErrorCovariance& covariance) {
  return covariance.diagonal().cwiseSqrt();
}

TEST(StartupAlignment, StandingStartsFromStillnessCompassAndDgps) {
  InertialNavigatorConfig config;
  config.p_body_gps_antenna = Eigen::Vector3d(0.2, 0.0, 0.5);
  Bench bench(config);
  bench.stand(0, 1'500'000'000);
  bench.compass(0, 1'500'000'000, kYaw);
  EXPECT_FALSE(bench.startup.standing(bench.history)) << "the window is not full yet";
  bench.stand(1'505'000'000, 2'100'000'000);
  // A disturbed reading is left out of the robust mean.
  bench.startup.addCompassYaw({2'050'000'000, kYaw + 0.5});
  const GpsFix fix{2'000'000'000, Eigen::Vector3d(100.0, 200.0, 5.0)};
  bench.startup.addGps(fix);
  const std::optional<NavigatorStart> start = bench.startup.standing(bench.history);
  ASSERT_TRUE(start);
  EXPECT_EQ(start->state.stamp_ns, 2'100'000'000);
  EXPECT_EQ(start->imu.stamp_ns, 2'100'000'000);
  const Eigen::Vector3d euler = start->state.q_world_body.toRotationMatrix().eulerAngles(2, 1, 0);
  EXPECT_NEAR(euler(0), kYaw, 1e-9);
  EXPECT_NEAR(euler(1), kPitch, 1e-9);
  EXPECT_NEAR(euler(2), kRoll, 1e-9);
  EXPECT_TRUE(start->state.p_world_body.isApprox(
      fix.p_world_antenna - start->state.q_world_body * config.p_body_gps_antenna, 1e-12));
  EXPECT_TRUE(start->state.v_world_body.isZero());
  EXPECT_TRUE(start->state.gyro_bias_radps.isApprox(kStandingGyroBias_radps, 1e-9));
  EXPECT_EQ(start->position, StartPosition::kFromSensors);
  EXPECT_TRUE(start->velocity_known);

  const ErrorVector sigma = sigmasOf(start->covariance);
  EXPECT_NEAR(sigma(kPosition), 5.0, 1e-12);
  EXPECT_NEAR(sigma(kPosition + 2), 10.0, 1e-12);
  EXPECT_NEAR(sigma(kVelocity), 0.05, 1e-12);
  // Tilt b_a / g, yaw one compass reading's hypot(white, shared).
  EXPECT_NEAR(sigma(kAttitude), 0.05 / kG, 1e-12);
  EXPECT_NEAR(sigma(kAttitude + 2), std::hypot(2.0, 2.0) * M_PI / 180.0, 1e-12);
  // The mean rate of white noise N over the 2 s window: N / sqrt(2 s).
  EXPECT_NEAR(sigma(kGyroBias), config.imu_noise.gyro_noise_radps_per_sqrt_hz / std::sqrt(2.0),
              1e-12);
  EXPECT_NEAR(sigma(kAccelBias), 0.05, 1e-12);
  EXPECT_TRUE(start->covariance.isDiagonal());
}

TEST(StartupAlignment, StandingWithoutDgpsKnowsNeitherPositionNorVelocity) {
  Bench bench;
  bench.stand(0, 2'100'000'000);
  bench.compass(1'000'000'000, 2'000'000'000, kYaw);
  const std::optional<NavigatorStart> start = bench.startup.standing(bench.history);
  ASSERT_TRUE(start);
  EXPECT_EQ(start->position, StartPosition::kUnknown);
  EXPECT_FALSE(start->velocity_known);
  const ErrorVector sigma = sigmasOf(start->covariance);
  EXPECT_DOUBLE_EQ(sigma(kPosition), 1e4);
  EXPECT_DOUBLE_EQ(sigma(kVelocity), bench.config.max_ground_speed_mps);
  // A window only the IMU calls still may be a cruise: no gyro bias from it.
  EXPECT_TRUE(start->state.gyro_bias_radps.isZero());
  EXPECT_DOUBLE_EQ(sigma(kGyroBias), bench.config.gyro_turn_on_bias_sigma_radps);
}

TEST(StartupAlignment, AStandingStartNeedsASecondOfCompassReadings) {
  Bench bench;
  bench.stand(0, 2'100'000'000);
  bench.compass(1'200'000'000, 2'000'000'000, kYaw);  // nine readings
  EXPECT_FALSE(bench.startup.standing(bench.history));
  bench.startup.addCompassYaw({2'050'000'000, kYaw});
  EXPECT_TRUE(bench.startup.standing(bench.history));
  // Those older than the still window drop out.
  bench.startup.prune(3'250'000'000);
  EXPECT_FALSE(bench.startup.standing(bench.history));
}

TEST(StartupAlignment, OneMovingDopplerEpochHoldsTheStandingStartAndTwoBarIt) {
  Bench bench;
  bench.stand(0, 2'100'000'000);
  bench.compass(1'000'000'000, 2'000'000'000, kYaw);
  bench.startup.addGps({2'000'000'000, Eigen::Vector3d::Zero()});
  ASSERT_TRUE(bench.startup.standing(bench.history));
  const Eigen::Vector2d moving(1.0, 0.0);  // beyond 4 sigma of 0.1 m/s
  EXPECT_FALSE(bench.startup.addGpsVelocity({1'000'000'000, moving}));
  EXPECT_FALSE(bench.startup.standing(bench.history));
  // The next epoch denies it: multipath, counted gated.
  EXPECT_TRUE(bench.startup.addGpsVelocity({2'000'000'000, Eigen::Vector2d(0.3, 0.0)}));
  EXPECT_TRUE(bench.startup.standing(bench.history));
  // Two in a row: the robot moves, and stays barred.
  EXPECT_FALSE(bench.startup.addGpsVelocity({3'000'000'000, moving}));
  EXPECT_FALSE(bench.startup.addGpsVelocity({4'000'000'000, moving}));
  EXPECT_TRUE(bench.startup.addGpsVelocity({5'000'000'000, Eigen::Vector2d::Zero()}));
  EXPECT_FALSE(bench.startup.standing(bench.history));
}

// Driving level at kYaw and speeding up at 0.5 m/s^2: DGPS velocities of 1
// and 1.5 m/s a second apart.
std::optional<NavigatorStart> startInMotion(const std::optional<GpsFix>& fix) {
  Bench bench;
  const Eigen::Vector2d heading(std::cos(kYaw), std::sin(kYaw));
  const ImuSample speeding_up{0, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.5, 0.0, kG)};
  const auto drive = [&](int64_t from_ns, int64_t to_ns) {
    for (int64_t t = from_ns; t <= to_ns; t += kSamplePeriod_ns) {
      bench.addImu({t, speeding_up.gyro_radps, speeding_up.accel_mps2});
    }
  };
  drive(2'000'000'000, 3'000'000'000);
  bench.compass(2'000'000'000, 4'000'000'000, kYaw);
  if (fix) {
    bench.startup.addGps(*fix);
  }
  EXPECT_FALSE(bench.startup.addGpsVelocity({3'000'000'000, 1.0 * heading}));
  EXPECT_FALSE(bench.startup.inMotion(bench.history));
  drive(3'005'000'000, 4'000'000'000);
  EXPECT_FALSE(bench.startup.addGpsVelocity({4'000'000'000, 1.5 * heading}));
  EXPECT_FALSE(bench.startup.inMotion(bench.history)) << "the IMU has not passed the velocity";
  EXPECT_FALSE(bench.startup.standing(bench.history));
  drive(4'005'000'000, 4'005'000'000);
  std::optional<NavigatorStart> start = bench.startup.inMotion(bench.history);
  EXPECT_FALSE(bench.startup.inMotion(bench.history)) << "tried once per pair";
  return start;
}

TEST(StartupAlignment, StartsInMotionFromTwoDgpsVelocities) {
  const std::optional<NavigatorStart> start = startInMotion(std::nullopt);
  ASSERT_TRUE(start);
  EXPECT_EQ(start->state.stamp_ns, 4'000'000'000);
  EXPECT_EQ(start->imu.stamp_ns, 4'000'000'000);
  EXPECT_NEAR(yawOf(start->state.q_world_body), kYaw, 1e-6);
  EXPECT_LT((start->state.q_world_body.toRotationMatrix() * Eigen::Vector3d::UnitZ() -
             Eigen::Vector3d::UnitZ())
                .norm(),
            1e-6);
  EXPECT_TRUE(start->state.v_world_body.isApprox(
      Eigen::Vector3d(1.5 * std::cos(kYaw), 1.5 * std::sin(kYaw), 0.0), 1e-12));
  EXPECT_EQ(start->position, StartPosition::kUnknown);
  const ErrorVector sigma = sigmasOf(start->covariance);
  EXPECT_NEAR(sigma(kVelocity), 0.1, 1e-12);
  // The vertical velocity within a steep street's grade times the speed.
  EXPECT_NEAR(sigma(kVelocity + 2), 0.08 * 1.5, 1e-12);
  EXPECT_GT(sigma(kAttitude), 0.0);
  EXPECT_EQ(sigma(kAttitude), sigma(kAttitude + 1));
  EXPECT_NEAR(sigma(kAttitude + 2), std::hypot(2.0, 2.0) * M_PI / 180.0, 1e-12);
  EXPECT_TRUE(start->state.gyro_bias_radps.isZero());
  EXPECT_NEAR(sigma(kGyroBias), 0.0035, 1e-12);

  const GpsFix same_epoch{4'010'000'000, Eigen::Vector3d(7.0, 8.0, 1.0)};
  const std::optional<NavigatorStart> placed = startInMotion(same_epoch);
  ASSERT_TRUE(placed);
  EXPECT_EQ(placed->position, StartPosition::kFromSensors);
  EXPECT_EQ(placed->state.p_world_body, same_epoch.p_world_antenna);
  EXPECT_NEAR(sigmasOf(placed->covariance)(kPosition), 5.0, 1e-12);
  const GpsFix older_epoch{3'000'000'000, same_epoch.p_world_antenna};
  EXPECT_EQ(startInMotion(older_epoch)->position, StartPosition::kUnknown);
}

VisionPayload cameraFix(
    const Eigen::Vector3d& p_world_body,
    const Eigen::Isometry3d& T_body_camera = InertialNavigatorConfig::defaultBodyCamera()) {
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
  T_world_body.linear() = Eigen::AngleAxisd(kYaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_world_body.translation() = p_world_body;
  VisionPayload fix;
  fix.T_world_camera.pose = T_world_body * T_body_camera;
  fix.T_world_camera.covariance = diagonalPoseCovariance(0.03, 0.002);
  fix.unproven_covariance = diagonalPoseCovariance(0.01, 0.0);
  return fix;
}

// A camera 0.5 m ahead of the body's origin and 1.2 m above it: the body's
// position error is the camera's plus its rotation error across the lever
// arm l = -R_world_body t_body_camera, Sigma_p + s_theta^2 (|l|^2 I - l l^T).
TEST(StartupAlignment, AVisionFixIsTheBodysPoseWithWhatTrackingMeasuredAndTheUnprovenPart) {
  Eigen::Isometry3d T_body_camera = InertialNavigatorConfig::defaultBodyCamera();
  T_body_camera.translation() = Eigen::Vector3d(0.5, 0.0, 1.2);
  const VisionPayload fix = cameraFix(Eigen::Vector3d(1.0, 2.0, 0.5), T_body_camera);
  const BodyFix body = bodyFixOf(7, fix, T_body_camera);
  EXPECT_EQ(body.stamp_ns, 7);
  EXPECT_TRUE(body.T_world_body.translation().isApprox(Eigen::Vector3d(1.0, 2.0, 0.5), 1e-12));
  EXPECT_NEAR(yawOf(Eigen::Quaterniond(body.T_world_body.linear())), kYaw, 1e-12);
  const Eigen::Vector3d lever = -(body.T_world_body.linear() * T_body_camera.translation());
  const Eigen::Matrix3d position_covariance =
      (0.03 * 0.03 - 0.01 * 0.01) * Eigen::Matrix3d::Identity() +
      0.002 * 0.002 *
          (lever.squaredNorm() * Eigen::Matrix3d::Identity() - lever * lever.transpose());
  EXPECT_TRUE((body.covariance.topLeftCorner<3, 3>().isApprox(position_covariance, 1e-12)));
  EXPECT_TRUE((body.covariance.bottomRightCorner<3, 3>().isApprox(
      0.002 * 0.002 * Eigen::Matrix3d::Identity(), 1e-12)));
  // U has no rotation part: no lever-arm term.
  EXPECT_TRUE(body.unproven_covariance.isApprox(fix.unproven_covariance, 1e-12));
}

TEST(StartupAlignment, AVisionFixStartsAStandingRobotAtRest) {
  Bench bench;
  bench.stand(0, 2'100'000'000);
  const BodyFix fix = bodyFixOf(2'052'500'000, cameraFix(Eigen::Vector3d(1.0, 2.0, 0.5)),
                                bench.config.T_body_camera);
  const std::optional<StartVelocity> velocity = bench.startup.addVisionFix(fix);
  ASSERT_TRUE(velocity);
  EXPECT_TRUE(velocity->v_world_mps.isZero());
  EXPECT_EQ(velocity->sigma_mps, 0.05);
  const std::optional<NavigatorStart> start =
      bench.startup.fromVision(fix, *velocity, bench.history);
  ASSERT_TRUE(start);
  EXPECT_EQ(start->position, StartPosition::kFromVision);
  EXPECT_EQ(start->state.stamp_ns, fix.stamp_ns);
  EXPECT_EQ(start->imu.stamp_ns, fix.stamp_ns);
  EXPECT_TRUE(start->state.p_world_body.isApprox(fix.T_world_body.translation(), 1e-12));
  EXPECT_TRUE(poseBlock(start->covariance).isApprox(fix.covariance, 1e-12));
  EXPECT_EQ(start->unproven_covariance, fix.unproven_covariance);
  EXPECT_NEAR(start->covariance(kVelocity, kVelocity), 0.05 * 0.05, 1e-15);
  EXPECT_TRUE(start->state.gyro_bias_radps.isApprox(kStandingGyroBias_radps, 1e-9));
  EXPECT_NEAR(start->covariance(kAccelBias, kAccelBias), 0.05 * 0.05, 1e-15);
  EXPECT_FALSE(bench.startup.fromVision(
      bodyFixOf(3'000'000'000, cameraFix(Eigen::Vector3d::Zero()), bench.config.T_body_camera),
      *velocity, bench.history))
      << "beyond the IMU";
}

// Before the still window is full, a fix starts the velocity from the one
// before it: v = dp / dt, sigma = sqrt(s_1^2 + s_2^2) / dt + a dt / 2.
TEST(StartupAlignment, AVisionFixBeforeTheWindowTakesTheVelocityOfTwo) {
  Bench bench;
  bench.stand(0, 500'000'000);
  const auto fixAt = [&](int64_t stamp_ns, double x_m) {
    return bodyFixOf(stamp_ns, cameraFix(Eigen::Vector3d(x_m, 0.0, 0.0)),
                     bench.config.T_body_camera);
  };
  EXPECT_FALSE(bench.startup.addVisionFix(fixAt(300'000'000, 0.0)));
  const std::optional<StartVelocity> velocity =
      bench.startup.addVisionFix(fixAt(400'000'000, 0.05));
  ASSERT_TRUE(velocity);
  EXPECT_TRUE(velocity->v_world_mps.isApprox(Eigen::Vector3d(0.5, 0.0, 0.0), 1e-9));
  const double position_variance_m2 = 0.03 * 0.03 - 0.01 * 0.01;  // R - U
  EXPECT_NEAR(velocity->sigma_mps, std::sqrt(2.0 * position_variance_m2) / 0.1 + 0.5 * 2.0 * 0.1,
              1e-9);
  EXPECT_FALSE(bench.startup.addVisionFix(fixAt(1'000'000'000, 0.1))) << "0.6 s apart";
  const std::optional<NavigatorStart> start =
      bench.startup.fromVision(fixAt(400'000'000, 0.05), *velocity, bench.history);
  ASSERT_TRUE(start);
  EXPECT_TRUE(start->state.gyro_bias_radps.isZero());
  EXPECT_NEAR(start->covariance(kGyroBias, kGyroBias), 0.0035 * 0.0035, 1e-15);
}

}  // namespace
}  // namespace lineloc
