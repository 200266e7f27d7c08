// The restarts: a run of gated vision fixes drifting together against the
// filter is fitted (r_i = a + b t_i, attitude constant) and restarts it with
// the drift, while fixes alternating between two offsets, or gated for less
// than vision_gated_restart_after_ns, do not; a run of gated compass readings
// agreeing on an offset turns the heading by it, while a wandering compass,
// or a run an accepted reading or vision fix ends, does not.
#include "robot/inertial/restart_monitor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "common/stats/chi_square.h"
#include "robot/inertial/measurement_models.h"

namespace lineloc {
namespace {

constexpr int64_t kSamplePeriod_ns = 5'000'000;  // 200 Hz
constexpr double kFixSigma_m = 0.03;

// Gated fixes at 10 Hz over a second whose position residuals are a + b t,
// and attitude residuals theta, the newest first as the history holds them.
struct FixRun {
  FixRun(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& theta) {
    fix.T_world_camera.covariance = diagonalPoseCovariance(kFixSigma_m, 0.002);
    for (int64_t k = 10; k >= 0; --k) {
      const double t_s = 0.1 * static_cast<double>(k);
      GatedFix gated;
      gated.stamp_ns = k * 100'000'000;
      gated.vision = &fix;
      gated.residual << a + b * t_s, theta;
      run.push_back(gated);
    }
  }
  VisionPayload fix;
  std::vector<GatedFix> run;
};

const double kGate3 = chiSquareQuantile(0.999, 3.0);

// sum_i (t_i - t_mean)^2 over t = 0, 0.1, ..., 1 s.
constexpr double kTimeSpread_s2 = 1.1;

TEST(CommonResidualDrift, FitsTheDriftAndOffsetTheFixesShare) {
  const Eigen::Vector3d b(0.3, 0.1, 0.0);
  const Eigen::Vector3d theta(0.01, -0.02, 0.03);
  const FixRun fixes(Eigen::Vector3d(0.5, -0.2, 0.1), b, theta);
  const std::optional<ResidualDrift> drift = commonResidualDrift(fixes.run, kGate3);
  ASSERT_TRUE(drift);
  EXPECT_TRUE(drift->velocity_mps.isApprox(b, 1e-9));
  EXPECT_TRUE(drift->attitude_offset_rad.isApprox(theta, 1e-12));
  EXPECT_NEAR(drift->velocity_variance, kFixSigma_m * kFixSigma_m / kTimeSpread_s2, 1e-12);
}

TEST(CommonResidualDrift, FixesAlternatingBetweenTwoOffsetsShareNone) {
  FixRun fixes(Eigen::Vector3d(0.0, 0.3, 0.0), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  for (size_t i = 0; i < fixes.run.size(); i += 2) {
    fixes.run[i].residual.x() += 0.6;
  }
  EXPECT_FALSE(commonResidualDrift(fixes.run, kGate3));

  // Likewise attitudes alternating 0.02 rad (ten of their sigmas) apart.
  FixRun turning(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  for (size_t i = 0; i < turning.run.size(); i += 2) {
    turning.run[i].residual(5) += 0.02;
  }
  EXPECT_FALSE(commonResidualDrift(turning.run, kGate3));
}

// A filter sure of a standing robot at the origin, facing east, and vision
// fixes of the body's position `p_world_body(k)` at 10 Hz from 0.1 s, each
// delivered 50 ms late; after each, the restart the monitor calls for.
struct GatedFixesRun {
  std::optional<VisionRestart> first_restart;
  int fixes_before_restart = 0;
  // The largest velocity variance of the filter at the restart's fix.
  double filter_velocity_variance = 0.0;
};

GatedFixesRun deliverFixes(const std::function<Eigen::Vector3d(int)>& p_world_body, int fix_count,
                           const InertialNavigatorConfig& config = InertialNavigatorConfig{}) {
  const NavigationFilter filter(config);
  const VisionRestartMonitor monitor(config);
  MeasurementHistory history(config.history_ns);
  const ImuSample standing{0, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, 9.80665)};
  history.addImu({standing, false}, filter);
  FilterSnapshot sure;
  sure.imu = standing;
  sure.covariance = ErrorCovariance::Identity() * 1e-4;
  history.start(sure, filter);
  GatedFixesRun outcome;
  int next_fix = 1;
  const auto fixStamp = [](int64_t k) { return k * 100'000'000 + 2'500'000; };
  for (int64_t t = kSamplePeriod_ns; next_fix <= fix_count; t += kSamplePeriod_ns) {
    history.addImu({{t, standing.gyro_radps, standing.accel_mps2}, false}, filter);
    if (fixStamp(next_fix) + 50'000'000 > t) {
      continue;
    }
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    T_world_body.translation() = p_world_body(next_fix);
    VisionPayload fix;
    fix.T_world_camera.pose = T_world_body * config.T_body_camera;
    fix.T_world_camera.covariance = diagonalPoseCovariance(kFixSigma_m, 0.002);
    EXPECT_EQ(history.add(fixStamp(next_fix), Measurement(fix), filter),
              MeasurementOutcome::kGated);
    ++next_fix;
    if (const std::optional<VisionRestart> restart = monitor.restart(history)) {
      if (!outcome.first_restart) {
        outcome.first_restart = restart;
        outcome.fixes_before_restart = next_fix - 1;
        outcome.filter_velocity_variance = history.at(restart->fix.stamp_ns)
                                               .covariance.block<3, 3>(kVelocity, kVelocity)
                                               .diagonal()
                                               .maxCoeff();
      }
    }
  }
  return outcome;
}

// 3 m off and drifting away at 0.4 m/s: restarted once the gated fixes span
// a second (0.1 to 1.1 s), from the newest, with the drift as velocity and
// its variance the filter's plus sigma_p^2 / sum (t_i - t_mean)^2.
TEST(VisionRestartMonitor, FixesGatedForASecondDriftingTogetherRestartTheFilter) {
  const auto drifting = [](int k) { return Eigen::Vector3d(3.0 + 0.04 * k, 0.0, 0.0); };
  const GatedFixesRun run = deliverFixes(drifting, 15);
  ASSERT_TRUE(run.first_restart);
  EXPECT_EQ(run.fixes_before_restart, 11);
  const VisionRestart& restart = *run.first_restart;
  EXPECT_EQ(restart.fix.stamp_ns, 1'102'500'000);
  EXPECT_TRUE(restart.fix.T_world_body.translation().isApprox(drifting(11), 1e-9));
  EXPECT_TRUE(restart.velocity.v_world_mps.isApprox(Eigen::Vector3d(0.4, 0.0, 0.0), 1e-6));
  EXPECT_NEAR(restart.velocity.sigma_mps,
              std::sqrt(run.filter_velocity_variance + kFixSigma_m * kFixSigma_m / kTimeSpread_s2),
              1e-9);
}

TEST(VisionRestartMonitor, FixesSwitchingBetweenTwoWrongPosesOrGatedBrieflyRestartNothing) {
  const GatedFixesRun switching =
      deliverFixes([](int k) { return Eigen::Vector3d(k % 2 == 0 ? 3.3 : 2.7, 0.3, 0.0); }, 30);
  EXPECT_FALSE(switching.first_restart);

  InertialNavigatorConfig patient;
  patient.vision_gated_restart_after_ns = 2'000'000'000;
  const auto drifting = [](int k) { return Eigen::Vector3d(3.0 + 0.04 * k, 0.0, 0.0); };
  EXPECT_FALSE(deliverFixes(drifting, 15, patient).first_restart);
  InertialNavigatorConfig never;
  never.vision_gated_restart_after_ns = 0;
  EXPECT_FALSE(deliverFixes(drifting, 15, never).first_restart);
}

Measurement compassReading(std::optional<MeasurementOutcome> outcome, double residual_rad) {
  Measurement reading(YawPayload{0.0});
  reading.outcome = outcome;
  reading.yaw_residual_rad = residual_rad;
  return reading;
}

Measurement visionFix(MeasurementOutcome outcome) {
  Measurement fix(VisionPayload{});
  fix.outcome = outcome;
  return fix;
}

// Feeds readings gated at 10 Hz over [from_s, to_s) with the residual
// `residual_rad(k)` of the k-th; returns the first restart.
std::optional<NavigatorStart> feedGated(CompassRestartMonitor& monitor,
                                        const FilterSnapshot& latest, double from_s, double to_s,
                                        const std::function<double(int)>& residual_rad) {
  int k = 0;
  for (double t_s = from_s; t_s < to_s - 1e-9; t_s += 0.1, ++k) {
    monitor.add(static_cast<int64_t>(std::llround(t_s * 1e9)),
                compassReading(MeasurementOutcome::kGated, residual_rad(k)));
    if (std::optional<NavigatorStart> start = monitor.restart(latest)) {
      return start;
    }
  }
  return std::nullopt;
}

FilterSnapshot movingNorthEast() {
  FilterSnapshot latest;
  latest.state.stamp_ns = 12'000'000'000;
  latest.state.q_world_body = Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()));
  latest.state.v_world_body = Eigen::Vector3d(1.0, 0.0, 0.0);
  latest.covariance = ErrorCovariance::Constant(1e-3) + ErrorCovariance::Identity() * 0.01;
  latest.imu.stamp_ns = latest.state.stamp_ns;
  latest.position_known = false;
  latest.velocity_known = false;
  latest.fixes.unproven_covariance = diagonalPoseCovariance(0.15, 0.0);
  return latest;
}

// Readings 0.4 rad off the filter's heading, +-0.01 about it, gated for 8 s:
// the heading and velocity turn by 0.4 rad, the yaw's variance is one
// reading's again, uncorrelated, and the rest of the filter stays.
TEST(CompassRestartMonitor, GatedReadingsAgreeingOnAnOffsetTurnTheHeading) {
  const InertialNavigatorConfig config;
  CompassRestartMonitor monitor(config);
  const FilterSnapshot latest = movingNorthEast();
  const std::optional<NavigatorStart> start =
      feedGated(monitor, latest, 0.0, 9.0, [](int k) { return 0.4 + (k % 2 == 0 ? 0.01 : -0.01); });
  ASSERT_TRUE(start);
  EXPECT_NEAR(yawOf(start->state.q_world_body), 0.5, 1e-3);
  EXPECT_TRUE(
      start->state.v_world_body.isApprox(Eigen::Vector3d(std::cos(0.4), std::sin(0.4), 0.0), 1e-3));
  const double yaw_sigma_rad = compassYawSigma_rad(config);
  for (int i = 0; i < kErrorStateSize; ++i) {
    for (int j = 0; j < kErrorStateSize; ++j) {
      const bool yaw = i == kAttitude + 2 || j == kAttitude + 2;
      const double expected =
          i == j && yaw ? yaw_sigma_rad * yaw_sigma_rad : (yaw ? 0.0 : latest.covariance(i, j));
      EXPECT_EQ(start->covariance(i, j), expected) << i << ", " << j;
    }
  }
  EXPECT_EQ(start->imu.stamp_ns, latest.imu.stamp_ns);
  EXPECT_EQ(start->position, StartPosition::kUnknown);
  EXPECT_FALSE(start->velocity_known);
  EXPECT_EQ(start->unproven_covariance, latest.fixes.unproven_covariance);
}

TEST(CompassRestartMonitor, AWanderingCompassRestartsNothing) {
  CompassRestartMonitor monitor{InertialNavigatorConfig{}};
  EXPECT_FALSE(feedGated(monitor, movingNorthEast(), 0.0, 30.0,
                         [](int k) { return k % 2 == 0 ? 0.4 : -0.4; }));
}

TEST(CompassRestartMonitor, AnAcceptedReadingOrVisionFixEndsTheRun) {
  const InertialNavigatorConfig config;
  const FilterSnapshot latest = movingNorthEast();
  const auto offset = [](int) { return 0.4; };
  for (const Measurement& ending : {compassReading(MeasurementOutcome::kAccepted, 0.0),
                                    visionFix(MeasurementOutcome::kAccepted)}) {
    CompassRestartMonitor monitor(config);
    EXPECT_FALSE(feedGated(monitor, latest, 0.0, 5.0, offset));
    monitor.add(5'000'000'000, ending);
    EXPECT_FALSE(feedGated(monitor, latest, 5.1, 12.0, offset));
  }
  // A gated vision fix, a reading pending or skipped, end nothing.
  CompassRestartMonitor monitor(config);
  EXPECT_FALSE(feedGated(monitor, latest, 0.0, 5.0, offset));
  monitor.add(5'000'000'000, visionFix(MeasurementOutcome::kGated));
  monitor.add(5'000'000'000, compassReading(MeasurementOutcome::kSkipped, 0.0));
  monitor.add(5'000'000'000, compassReading(std::nullopt, 0.0));
  EXPECT_TRUE(feedGated(monitor, latest, 5.1, 12.0, offset));

  InertialNavigatorConfig never = config;
  never.compass_gated_restart_after_ns = 0;
  CompassRestartMonitor disabled(never);
  EXPECT_FALSE(feedGated(disabled, latest, 0.0, 30.0, offset));
}

}  // namespace
}  // namespace lineloc
