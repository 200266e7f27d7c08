// The filter's history: a measurement delivered late gives the very state it
// gives on time, one older than the history is refused, a replay that changes
// a measurement's outcome moves its count, pruning hands back what left the
// history in time order, and predictions interpolate the rates between
// samples and hold them past the last.
#include "robot/inertial/measurement_history.h"

#include <gtest/gtest.h>

#include <vector>

#include "robot/inertial/measurement_models.h"

namespace lineloc {
namespace {

constexpr int64_t kSamplePeriod_ns = 5'000'000;  // 200 Hz

// A robot turning and speeding up, its rates changing from sample to sample
// so that interpolating them matters.
ImuSample sampleAt(int64_t stamp_ns) {
  const double t_s = static_cast<double>(stamp_ns) * 1e-9;
  return {stamp_ns, Eigen::Vector3d(0.01, -0.02, 0.2 + 0.5 * t_s),
          Eigen::Vector3d(0.3 + t_s, 0.1, 9.80665)};
}

// Every fourth sample still, so that replays run zero-velocity updates too.
BufferedImu bufferedAt(int64_t stamp_ns) {
  return {sampleAt(stamp_ns), stamp_ns % (4 * kSamplePeriod_ns) == 0};
}

FilterSnapshot startAtZero(double position_sigma_m = 0.1) {
  FilterSnapshot snapshot;
  snapshot.imu = sampleAt(0);
  ErrorVector sigma;
  sigma << Eigen::Vector3d::Constant(position_sigma_m), Eigen::Vector3d::Constant(0.05),
      Eigen::Vector3d::Constant(0.01), Eigen::Vector3d::Constant(0.0035),
      Eigen::Vector3d::Constant(0.05);
  snapshot.covariance = sigma.cwiseAbs2().asDiagonal();
  return snapshot;
}

// A history started at time zero whose IMU has reached `until_ns`.
MeasurementHistory historyUntil(int64_t until_ns, const NavigationFilter& filter,
                                int64_t history_ns = 3'000'000'000,
                                const FilterSnapshot& start = startAtZero()) {
  MeasurementHistory history(history_ns);
  history.addImu(bufferedAt(0), filter);
  history.start(start, filter);
  for (int64_t t = kSamplePeriod_ns; t <= until_ns; t += kSamplePeriod_ns) {
    history.addImu(bufferedAt(t), filter);
  }
  return history;
}

// The camera's pose the filter predicts at `stamp_ns`, 2 cm off, as a fix of
// `sigma_m` (and 0.1 degrees).
Measurement visionFixAt(int64_t stamp_ns, const NavigationFilter& filter, double sigma_m = 0.03) {
  const FilterSnapshot predicted = historyUntil(stamp_ns, filter).predict(stamp_ns, filter);
  VisionPayload fix;
  fix.T_world_camera.pose = cameraPoseOf(predicted.state, predicted.covariance,
                                         InertialNavigatorConfig::defaultBodyCamera())
                                .pose;
  fix.T_world_camera.pose.translation() += Eigen::Vector3d(0.02, 0.0, 0.0);
  fix.T_world_camera.covariance = diagonalPoseCovariance(sigma_m, 0.1 * M_PI / 180.0);
  return Measurement(fix);
}

Measurement gpsFixAt(int64_t stamp_ns, const NavigationFilter& filter) {
  return Measurement(
      GpsPayload{historyUntil(stamp_ns, filter).predict(stamp_ns, filter).state.p_world_body,
                 Eigen::Vector3d(25.0, 25.0, 100.0).asDiagonal()});
}

void expectSameFilter(const FilterSnapshot& a, const FilterSnapshot& b) {
  EXPECT_EQ(a.state.stamp_ns, b.state.stamp_ns);
  EXPECT_EQ(a.state.p_world_body, b.state.p_world_body);
  EXPECT_EQ(a.state.v_world_body, b.state.v_world_body);
  EXPECT_EQ(a.state.q_world_body.coeffs(), b.state.q_world_body.coeffs());
  EXPECT_EQ(a.state.gyro_bias_radps, b.state.gyro_bias_radps);
  EXPECT_EQ(a.state.accel_bias_mps2, b.state.accel_bias_mps2);
  EXPECT_EQ(a.covariance, b.covariance);
  EXPECT_EQ(a.zero_velocity_updates, b.zero_velocity_updates);
}

void expectSameCounts(const MeasurementCounters& a, const MeasurementCounters& b) {
  EXPECT_EQ(a.accepted, b.accepted);
  EXPECT_EQ(a.gated, b.gated);
  EXPECT_EQ(a.degenerate, b.degenerate);
  EXPECT_EQ(a.skipped, b.skipped);
  EXPECT_EQ(a.too_late, b.too_late);
  EXPECT_EQ(a.invalid, b.invalid);
}

TEST(MeasurementHistory, ALateMeasurementGivesTheStateOfAnOnTimeOne) {
  const NavigationFilter filter{InertialNavigatorConfig{}};
  // Between samples but one, so that each splits an IMU interval.
  const std::vector<std::pair<int64_t, Measurement>> measurements = {
      {52'500'000, visionFixAt(52'500'000, filter)},
      {81'000'000, Measurement(YawPayload{0.01})},
      {120'000'000, gpsFixAt(120'000'000, filter)},
      {151'000'000, Measurement(GpsVelocityPayload{Eigen::Vector2d(0.05, 0.0)})}};
  constexpr int64_t kLatency_ns = 40'000'000;
  MeasurementHistory on_time = historyUntil(0, filter);
  MeasurementHistory late = historyUntil(0, filter);
  size_t next_on_time = 0;
  size_t next_late = 0;
  for (int64_t t = kSamplePeriod_ns; t <= 300'000'000; t += kSamplePeriod_ns) {
    for (; next_on_time < measurements.size() && measurements[next_on_time].first <= t;
         ++next_on_time) {
      const auto& [stamp_ns, measurement] = measurements[next_on_time];
      EXPECT_EQ(on_time.add(stamp_ns, measurement, filter), MeasurementOutcome::kPending);
    }
    for (; next_late < measurements.size() && measurements[next_late].first + kLatency_ns <= t;
         ++next_late) {
      const auto& [stamp_ns, measurement] = measurements[next_late];
      EXPECT_NE(late.add(stamp_ns, measurement, filter), MeasurementOutcome::kPending);
    }
    on_time.addImu(bufferedAt(t), filter);
    late.addImu(bufferedAt(t), filter);
  }
  ASSERT_EQ(next_late, measurements.size());
  expectSameFilter(on_time.latest(), late.latest());
  EXPECT_GT(late.latest().zero_velocity_updates, 0);
  for (const auto& [stamp_ns, measurement] : late.measurements()) {
    EXPECT_EQ(measurement.outcome, on_time.measurements().find(stamp_ns)->second.outcome);
  }
  EXPECT_EQ(late.counters(MeasurementKind::kVision).accepted, 1);
  for (const MeasurementKind kind : {MeasurementKind::kVision, MeasurementKind::kGps,
                                     MeasurementKind::kGpsVelocity, MeasurementKind::kCompass}) {
    expectSameCounts(on_time.counters(kind), late.counters(kind));
  }
}

TEST(MeasurementHistory, AMeasurementAtOrBeforeItsOldestSnapshotIsTooLate) {
  const NavigationFilter filter{InertialNavigatorConfig{}};
  MeasurementHistory history = historyUntil(50'000'000, filter);
  EXPECT_EQ(history.add(0, gpsFixAt(0, filter), filter), MeasurementOutcome::kTooLate);
  EXPECT_EQ(history.add(-1, gpsFixAt(0, filter), filter), MeasurementOutcome::kTooLate);
  EXPECT_EQ(history.counters(MeasurementKind::kGps).too_late, 2);
  EXPECT_EQ(history.counters(MeasurementKind::kGps).rejected(), 2);
  EXPECT_TRUE(history.measurements().empty());
  EXPECT_EQ(history.latest().state.stamp_ns, 50'000'000);
}

// A DGPS fix bounds a position known to 10 m; a vision fix before it, come
// late, leaves the position known to centimetres, and the DGPS fix, replayed
// after it, adds nothing: its count moves from accepted to skipped.
TEST(MeasurementHistory, AReplayThatChangesAnOutcomeMovesItsCount) {
  const NavigationFilter filter{InertialNavigatorConfig{}};
  const FilterSnapshot uncertain = startAtZero(10.0);
  MeasurementHistory history = historyUntil(150'000'000, filter, 3'000'000'000, uncertain);
  EXPECT_EQ(history.add(100'000'000, gpsFixAt(100'000'000, filter), filter),
            MeasurementOutcome::kAccepted);
  EXPECT_EQ(history.counters(MeasurementKind::kGps).accepted, 1);
  EXPECT_EQ(history.add(50'000'000, visionFixAt(50'000'000, filter), filter),
            MeasurementOutcome::kAccepted);
  EXPECT_EQ(history.counters(MeasurementKind::kGps).accepted, 0);
  EXPECT_EQ(history.counters(MeasurementKind::kGps).skipped, 1);
  EXPECT_EQ(history.counters(MeasurementKind::kVision).accepted, 1);
  EXPECT_EQ(history.measurements().find(100'000'000)->second.outcome, MeasurementOutcome::kSkipped);
  // Replayed again, unchanged outcomes are counted once.
  EXPECT_EQ(
      history.add(20'000'000, Measurement(GpsVelocityPayload{Eigen::Vector2d::Zero()}), filter),
      MeasurementOutcome::kAccepted);
  EXPECT_EQ(history.counters(MeasurementKind::kGps).skipped, 1);
  EXPECT_EQ(history.counters(MeasurementKind::kVision).accepted, 1);
}

TEST(MeasurementHistory, PruningHandsBackWhatLeftTheHistoryOldestFirst) {
  const NavigationFilter filter{InertialNavigatorConfig{}};
  constexpr int64_t kHistory_ns = 50'000'000;
  MeasurementHistory history = historyUntil(40'000'000, filter, kHistory_ns);
  const Measurement velocity(GpsVelocityPayload{Eigen::Vector2d::Zero()});
  history.add(20'000'000, velocity, filter);
  history.add(10'000'000, gpsFixAt(10'000'000, filter), filter);
  history.add(70'000'000, velocity, filter);
  for (int64_t t = 45'000'000; t <= 100'000'000; t += kSamplePeriod_ns) {
    history.addImu(bufferedAt(t), filter);
  }
  const std::vector<std::pair<int64_t, Measurement>> dropped = history.prune();
  ASSERT_EQ(dropped.size(), 2u);
  EXPECT_EQ(dropped[0].first, 10'000'000);
  EXPECT_EQ(dropped[0].second.kind(), MeasurementKind::kGps);
  EXPECT_EQ(dropped[0].second.outcome, MeasurementOutcome::kSkipped);
  EXPECT_EQ(dropped[1].first, 20'000'000);
  EXPECT_EQ(dropped[1].second.outcome, MeasurementOutcome::kAccepted);
  EXPECT_EQ(history.measurements().size(), 1u);
  // The last snapshot at or before 100 - 50 ms, and the one sample at it.
  EXPECT_EQ(history.oldest().state.stamp_ns, 50'000'000);
  EXPECT_TRUE(history.imuAt(50'000'000));
  EXPECT_FALSE(history.imuAt(49'000'000));
  EXPECT_EQ(history.add(50'000'000, velocity, filter), MeasurementOutcome::kTooLate);
  // Dropped, they stay counted.
  EXPECT_EQ(history.counters(MeasurementKind::kGpsVelocity).accepted, 2);
  EXPECT_EQ(history.counters(MeasurementKind::kGps).skipped, 1);
}

TEST(MeasurementHistory, PredictsWithRatesInterpolatedBetweenSamplesAndHeldPastTheLast) {
  const NavigationFilter filter{InertialNavigatorConfig{}};
  const MeasurementHistory history = historyUntil(100'000'000, filter);
  expectSameFilter(history.predict(50'000'000, filter), history.at(50'000'000));
  EXPECT_EQ(&history.at(52'500'000), &history.at(50'000'000));
  EXPECT_EQ(&history.at(-1), &history.oldest());

  FilterSnapshot between = history.at(50'000'000);
  filter.propagate(between.imu,
                   interpolateImu(sampleAt(50'000'000), sampleAt(55'000'000), 52'500'000), between);
  expectSameFilter(history.predict(52'500'000, filter), between);

  FilterSnapshot beyond = history.latest();
  ImuSample held = beyond.imu;
  held.stamp_ns = 120'000'000;
  filter.propagate(beyond.imu, held, beyond);
  expectSameFilter(history.predict(120'000'000, filter), beyond);
}

TEST(MeasurementHistory, AStartStepsThroughTheSamplesBufferedAfterIt) {
  const NavigationFilter filter{InertialNavigatorConfig{}};
  MeasurementHistory buffered_first(3'000'000'000);
  for (int64_t t = 0; t <= 100'000'000; t += kSamplePeriod_ns) {
    buffered_first.addImu(bufferedAt(t), filter);
  }
  EXPECT_FALSE(buffered_first.started());
  EXPECT_EQ(buffered_first.latestImu()->stamp_ns, 100'000'000);
  buffered_first.start(startAtZero(), filter);
  ASSERT_TRUE(buffered_first.started());
  expectSameFilter(buffered_first.latest(), historyUntil(100'000'000, filter).latest());
}

}  // namespace
}  // namespace lineloc
