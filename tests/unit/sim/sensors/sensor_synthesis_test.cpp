#include "sim/sensors/sensor_synthesis.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/nmea/nmea_sentence.h"

namespace lineloc::sim {
namespace {

TrajectoryConfig shortDrive(uint64_t seed) {
  TrajectoryConfig config;
  config.seed = seed;
  config.duration_s = 120.0;
  return config;
}

TEST(GroundTruthTrajectory, DeterministicPerSeed) {
  const GroundTruthTrajectory a(shortDrive(7));
  const GroundTruthTrajectory b(shortDrive(7));
  const GroundTruthTrajectory c(shortDrive(8));
  const int64_t t = a.startStamp_ns() + 100'000'000'000;
  EXPECT_EQ(a.at(t).p_world_body, b.at(t).p_world_body);
  EXPECT_GT((a.at(t).p_world_body - c.at(t).p_world_body).norm(), 1.0);
}

TEST(GroundTruthTrajectory, StandsStillThenDrivesWithinSpeedLimits) {
  const GroundTruthTrajectory trajectory(shortDrive(3));
  const TrajectoryConfig& config = trajectory.config();
  const int64_t still_end = trajectory.startStamp_ns() + 4'900'000'000;
  EXPECT_EQ(trajectory.at(still_end).v_world_body.norm(), 0.0);
  EXPECT_EQ(trajectory.at(still_end).gyro_body_radps.norm(), 0.0);
  double max_speed = 0.0;
  bool stopped_later = false;
  for (int64_t t = still_end + 10'000'000'000; t < trajectory.endStamp_ns(); t += 100'000'000) {
    const double speed = trajectory.at(t).v_world_body.head<2>().norm();
    max_speed = std::max(max_speed, speed);
    stopped_later |= speed == 0.0;
  }
  EXPECT_LE(max_speed, config.max_speed_mps + 1e-12);
  EXPECT_GE(max_speed, config.min_speed_mps);
  EXPECT_TRUE(stopped_later) << "a 120 s drive with stop probability 0.15 per leg should stop";
}

// Velocity, acceleration and body rates must be the derivatives of position
// and attitude. Central differences over h = 1 ms have truncation error
// f''' h^2 / 6: jerk <= ~1 m/s^3 gives < 1e-6; rounding adds eps |p| / h ~ 1e-11.
TEST(GroundTruthTrajectory, DerivativesMatchFiniteDifferences) {
  const GroundTruthTrajectory trajectory(shortDrive(5));
  constexpr int64_t h_ns = 1'000'000;
  constexpr double h = 1e-3;
  for (int64_t t = trajectory.startStamp_ns() + 6'000'000'000; t < trajectory.endStamp_ns() - h_ns;
       t += 3'333'000'000) {
    const TruthSample before = trajectory.at(t - h_ns);
    const TruthSample now = trajectory.at(t);
    const TruthSample after = trajectory.at(t + h_ns);
    const Eigen::Vector3d velocity = (after.p_world_body - before.p_world_body) / (2 * h);
    const Eigen::Vector3d acceleration = (after.v_world_body - before.v_world_body) / (2 * h);
    EXPECT_LT((velocity - now.v_world_body).norm(), 1e-6);
    EXPECT_LT((acceleration - now.a_world_body).norm(), 1e-5);
    // R(t+h) = R(t-h) Exp(w 2h) to second order.
    const Eigen::AngleAxisd delta(before.q_world_body.conjugate() * after.q_world_body);
    const Eigen::Vector3d rate = delta.angle() * delta.axis() / (2 * h);
    EXPECT_LT((rate - now.gyro_body_radps).norm(), 1e-6);
  }
}

// The white noise of N samples has sample standard deviation within
// sigma (1 +- 3 / sqrt(2N)) at 99.7 %; with N = 24000 that is +-1.4 %.
TEST(SynthesiseImu, NoiseMatchesTheDensities) {
  const GroundTruthTrajectory trajectory(shortDrive(11));
  ImuModel noisy;
  ImuModel exact;
  exact.noise = false;
  const auto with_noise = synthesiseImu(trajectory, noisy, 1);
  const auto without = synthesiseImu(trajectory, exact, 1);
  ASSERT_EQ(with_noise.size(), without.size());
  ASSERT_EQ(with_noise.size(), 24001u);
  double gyro_sum_squares = 0.0;
  for (size_t i = 0; i < with_noise.size(); ++i) {
    const Eigen::Vector3d error =
        with_noise[i].gyro_radps - without[i].gyro_radps - with_noise[i].true_gyro_bias_radps;
    gyro_sum_squares += error.x() * error.x();
  }
  const double gyro_std = std::sqrt(gyro_sum_squares / static_cast<double>(with_noise.size()));
  const double expected = noisy.gyro_noise_radps_per_sqrt_hz * std::sqrt(noisy.rate_hz);
  EXPECT_NEAR(gyro_std / expected, 1.0, 3.0 / std::sqrt(2.0 * with_noise.size()));
  EXPECT_EQ(without.front().true_gyro_bias_radps.norm(), 0.0);
  EXPECT_EQ(synthesiseImu(trajectory, noisy, 1).back().accel_mps2, with_noise.back().accel_mps2);
}

TEST(SynthesiseGps, ErrorsAreMetresAndCorrelatedWithOutages) {
  TrajectoryConfig config = shortDrive(2);
  config.duration_s = 600.0;
  const GroundTruthTrajectory trajectory(config);
  GpsModel model;
  model.outage_probability = 0.02;
  const auto fixes = synthesiseGps(trajectory, model, 4);
  ASSERT_EQ(fixes.size(), 601u);
  double sum_squares = 0.0;
  double step_squares = 0.0;
  int invalid = 0;
  for (size_t i = 0; i < fixes.size(); ++i) {
    const Eigen::Vector2d error =
        (fixes[i].p_world_antenna - fixes[i].true_p_world_antenna).head<2>();
    sum_squares += error.squaredNorm();
    invalid += fixes[i].valid ? 0 : 1;
    if (i > 0) {
      const Eigen::Vector2d previous =
          (fixes[i - 1].p_world_antenna - fixes[i - 1].true_p_world_antenna).head<2>();
      step_squares += (error - previous).squaredNorm();
    }
  }
  // Horizontal RMS error sqrt(2) 4 m = 5.7 m, loosely (600 s is 10 correlation times).
  const double rms = std::sqrt(sum_squares / fixes.size());
  EXPECT_GT(rms, 2.5);
  EXPECT_LT(rms, 10.0);
  // Correlated: the error moves far less from one second to the next than its size.
  EXPECT_LT(std::sqrt(step_squares / fixes.size()), 0.25 * rms);
  EXPECT_GT(invalid, 0);
}

// With initial_horizontal_error_m = m the first fix's correlated horizontal
// error is m long (no white noise here), in the direction the stationary start
// would have had; every later draw is the same, so the difference from the
// stationary start's fixes is the start's difference times a^k, a =
// exp(-dt / correlation_time_s): the Gauss-Markov process forgetting its start.
TEST(SynthesiseGps, InitialErrorHasItsMagnitudeAndDecaysWithTheCorrelationTime) {
  TrajectoryConfig config = shortDrive(2);
  config.duration_s = 180.0;
  const GroundTruthTrajectory trajectory(config);
  GpsModel model;
  model.white_sigma_m = 0.0;
  const auto stationary = synthesiseGps(trajectory, model, 6);
  model.initial_horizontal_error_m = 10.0;
  const auto started = synthesiseGps(trajectory, model, 6);
  ASSERT_EQ(started.size(), 181u);
  ASSERT_EQ(started.size(), stationary.size());
  const auto horizontalError = [](const SimGpsFix& fix) -> Eigen::Vector2d {
    return (fix.p_world_antenna - fix.true_p_world_antenna).head<2>();
  };
  const Eigen::Vector2d first = horizontalError(started.front());
  EXPECT_NEAR(first.norm(), 10.0, 1e-9);
  EXPECT_NEAR(first.normalized().dot(horizontalError(stationary.front()).normalized()), 1.0, 1e-12);
  const double a = std::exp(-1.0 / model.correlation_time_s);
  const Eigen::Vector2d start_difference = first - horizontalError(stationary.front());
  for (size_t k = 0; k < started.size(); ++k) {
    const Eigen::Vector2d difference = horizontalError(started[k]) - horizontalError(stationary[k]);
    EXPECT_LT((difference - std::pow(a, static_cast<double>(k)) * start_difference).norm(), 1e-9)
        << "fix " << k;
    EXPECT_EQ(started[k].p_world_antenna.z(), stationary[k].p_world_antenna.z());
    EXPECT_EQ(started[k].valid, stationary[k].valid);
  }
}

// Over many seeds: the start's direction is uniform, and at fix k the error
// along it has mean m a^k and the error across it mean 0, each with variance
// sigma^2 (1 - a^2k), the stationary spread growing back.
TEST(SynthesiseGps, InitialErrorsMeanAndSpreadFollowTheGaussMarkovModel) {
  TrajectoryConfig config = shortDrive(2);
  config.duration_s = 120.0;
  const GroundTruthTrajectory trajectory(config);
  GpsModel model;
  model.white_sigma_m = 0.0;
  model.initial_horizontal_error_m = 10.0;
  constexpr int kSeeds = 400;
  const std::vector<size_t> ks = {0, 10, 60, 120};
  std::vector<double> along_sum(ks.size(), 0.0);
  std::vector<double> along_squares(ks.size(), 0.0);
  std::vector<double> across_squares(ks.size(), 0.0);
  Eigen::Vector2d direction_sum = Eigen::Vector2d::Zero();
  for (int seed = 0; seed < kSeeds; ++seed) {
    const auto fixes = synthesiseGps(trajectory, model, 1000 + seed);
    const Eigen::Vector2d start =
        (fixes.front().p_world_antenna - fixes.front().true_p_world_antenna).head<2>();
    const Eigen::Vector2d along = start.normalized();
    const Eigen::Vector2d across(-along.y(), along.x());
    direction_sum += along;
    for (size_t j = 0; j < ks.size(); ++j) {
      const Eigen::Vector2d error =
          (fixes[ks[j]].p_world_antenna - fixes[ks[j]].true_p_world_antenna).head<2>();
      along_sum[j] += error.dot(along);
      along_squares[j] += error.dot(along) * error.dot(along);
      across_squares[j] += error.dot(across) * error.dot(across);
    }
  }
  // The mean of n uniform unit vectors has E|mean|^2 = 1 / n.
  EXPECT_LT(direction_sum.norm() / kSeeds, 4.0 / std::sqrt(kSeeds));
  const double a = std::exp(-1.0 / model.correlation_time_s);
  const double sigma = model.correlated_horizontal_sigma_m;
  for (size_t j = 0; j < ks.size(); ++j) {
    SCOPED_TRACE("fix " + std::to_string(ks[j]));
    const double decay = std::pow(a, static_cast<double>(ks[j]));
    const double expected_mean = model.initial_horizontal_error_m * decay;
    const double variance = sigma * sigma * (1.0 - decay * decay);
    const double mean = along_sum[j] / kSeeds;
    // Five standard errors: sqrt(variance / n) for a mean, variance
    // sqrt(2 / n) for a normal sample's variance about a known mean.
    EXPECT_NEAR(mean, expected_mean, 5.0 * std::sqrt(variance / kSeeds) + 1e-9);
    const double along_variance = along_squares[j] / kSeeds - mean * mean;
    EXPECT_NEAR(along_variance, variance, 5.0 * variance * std::sqrt(2.0 / kSeeds) + 1e-9);
    EXPECT_NEAR(across_squares[j] / kSeeds, variance,
                5.0 * variance * std::sqrt(2.0 / kSeeds) + 1e-9);
  }
}

TEST(SynthesiseGps, NegativeInitialErrorIsRefused) {
  const GroundTruthTrajectory trajectory(shortDrive(1));
  GpsModel model;
  model.initial_horizontal_error_m = -1.0;
  EXPECT_THROW(synthesiseGps(trajectory, model, 1), std::invalid_argument);
  model.initial_horizontal_error_m = std::numeric_limits<double>::infinity();
  EXPECT_THROW(synthesiseGps(trajectory, model, 1), std::invalid_argument);
}

TEST(SynthesiseGps, NmeaEpochDecodesToTheSamePosition) {
  const GroundTruthTrajectory trajectory(shortDrive(1));
  const SiteProjection projection("UTM:31N", Eigen::Vector3d(593000.0, 5763000.0, 0.0));
  const auto fixes = synthesiseGps(trajectory, GpsModel{}, 3);
  const auto lines = formatNmeaEpoch(fixes[10], projection);
  ASSERT_EQ(lines.size(), 2u);
  const NmeaParseResult gga = parseNmeaSentence(lines[0]);
  ASSERT_EQ(gga.status, NmeaStatus::kOk) << lines[0];
  const auto& sentence = std::get<GgaSentence>(gga.sentence);
  const Eigen::Vector3d decoded =
      projection.toSite({sentence.latitude_deg, sentence.longitude_deg, sentence.altitude_msl_m});
  // 7 decimals of arc minutes (0.2 mm) and altitude to the millimetre.
  EXPECT_LT((decoded - fixes[10].p_world_antenna).norm(), 2e-3);
  const NmeaParseResult rmc = parseNmeaSentence(lines[1]);
  ASSERT_EQ(rmc.status, NmeaStatus::kOk) << lines[1];
  // Millisecond time in NMEA.
  const auto& velocity_sentence = std::get<RmcSentence>(rmc.sentence);
  EXPECT_EQ(velocity_sentence.utcStamp_ns(), fixes[10].stamp_ns / 1'000'000 * 1'000'000);
  // Speed and course give the velocity back: course = grid bearing - grid
  // bearing of true north, to 0.005 degrees and 0.0005 knots.
  ASSERT_TRUE(velocity_sentence.speed_knots && velocity_sentence.course_deg);
  const double speed_mps = *velocity_sentence.speed_knots * 1852.0 / 3600.0;
  ASSERT_GT(speed_mps, 0.1);
  const double grid_bearing_rad =
      *velocity_sentence.course_deg * M_PI / 180.0 +
      projection.gridBearingOfTrueNorth_rad(projection.toGeodetic(fixes[10].p_world_antenna));
  const Eigen::Vector2d velocity =
      speed_mps * Eigen::Vector2d(std::sin(grid_bearing_rad), std::cos(grid_bearing_rad));
  EXPECT_LT((velocity - fixes[10].v_world_antenna_mps).norm(), 1e-3);
}

// The velocity's error is white, 0.05 m/s per axis, and drawn apart from the
// position's: the positions of a seed are those it had before.
TEST(SynthesiseGps, VelocityIsDopplerNoiseOnTheTruth) {
  TrajectoryConfig config = shortDrive(2);
  config.duration_s = 600.0;
  const GroundTruthTrajectory trajectory(config);
  GpsModel model;
  const auto fixes = synthesiseGps(trajectory, model, 4);
  model.velocity_sigma_mps = 0.0;
  const auto exact = synthesiseGps(trajectory, model, 4);
  double sum_squares = 0.0;
  for (size_t i = 0; i < fixes.size(); ++i) {
    EXPECT_EQ(fixes[i].p_world_antenna, exact[i].p_world_antenna);
    EXPECT_EQ(exact[i].v_world_antenna_mps, exact[i].true_v_world_antenna_mps);
    sum_squares += (fixes[i].v_world_antenna_mps - fixes[i].true_v_world_antenna_mps).squaredNorm();
  }
  // 1202 squared normal deviates: their mean is 1 within 0.2 (5 of its sigmas).
  const double per_axis_sigma = std::sqrt(sum_squares / (2.0 * static_cast<double>(fixes.size())));
  EXPECT_NEAR(per_axis_sigma, 0.05, 0.2 * 0.05 / 2.0);
}

TEST(SynthesiseCompass, NoiseAndDisturbances) {
  TrajectoryConfig config = shortDrive(9);
  config.duration_s = 600.0;
  const GroundTruthTrajectory trajectory(config);
  CompassModel model;
  model.magnetic_declination_rad = 0.03;
  const double grid_bearing = -0.0186;
  const auto readings = synthesiseCompass(trajectory, model, grid_bearing, 5);
  ASSERT_EQ(readings.size(), 6001u);
  double sum_squares = 0.0;
  int clean = 0;
  int disturbed = 0;
  for (const SimCompassReading& r : readings) {
    const Eigen::Vector3d forward =
        trajectory.at(r.stamp_ns).q_world_body * Eigen::Vector3d::UnitX();
    const double expected = M_PI_2 - std::atan2(forward.y(), forward.x()) - grid_bearing - 0.03;
    const double error = std::remainder(r.magnetic_heading_rad - expected, 2.0 * M_PI);
    EXPECT_GE(r.magnetic_heading_rad, 0.0);
    EXPECT_LT(r.magnetic_heading_rad, 2.0 * M_PI);
    if (r.disturbed) {
      ++disturbed;
      EXPECT_GT(std::abs(error), model.min_disturbance_rad - 5 * model.sigma_rad);
    } else {
      ++clean;
      sum_squares += error * error;
    }
  }
  EXPECT_GT(disturbed, 0);
  EXPECT_NEAR(std::sqrt(sum_squares / clean) / model.sigma_rad, 1.0, 0.05);
}

// The bias is added to every reading: with the same seed each reading moves
// by exactly the bias, and the clean readings' mean error is the bias within
// five standard errors, sigma / sqrt(n).
TEST(SynthesiseCompass, BiasShiftsEveryReadingAndTheMeanByIt) {
  TrajectoryConfig config = shortDrive(9);
  config.duration_s = 600.0;
  const GroundTruthTrajectory trajectory(config);
  CompassModel model;
  const double grid_bearing = -0.0186;
  const auto unbiased = synthesiseCompass(trajectory, model, grid_bearing, 5);
  model.bias_rad = 5.0 * M_PI / 180.0;
  const auto biased = synthesiseCompass(trajectory, model, grid_bearing, 5);
  ASSERT_EQ(biased.size(), unbiased.size());
  double error_sum = 0.0;
  int clean = 0;
  for (size_t i = 0; i < biased.size(); ++i) {
    const SimCompassReading& r = biased[i];
    EXPECT_NEAR(
        std::remainder(r.magnetic_heading_rad - unbiased[i].magnetic_heading_rad, 2.0 * M_PI),
        model.bias_rad, 1e-12);
    EXPECT_GE(r.magnetic_heading_rad, 0.0);
    EXPECT_LT(r.magnetic_heading_rad, 2.0 * M_PI);
    if (r.disturbed) {
      continue;
    }
    const Eigen::Vector3d forward =
        trajectory.at(r.stamp_ns).q_world_body * Eigen::Vector3d::UnitX();
    const double expected = M_PI_2 - std::atan2(forward.y(), forward.x()) - grid_bearing;
    error_sum += std::remainder(r.magnetic_heading_rad - expected, 2.0 * M_PI);
    ++clean;
  }
  ASSERT_GT(clean, 1000);
  EXPECT_NEAR(error_sum / clean, model.bias_rad, 5.0 * model.sigma_rad / std::sqrt(clean));
}

TEST(SensorFiles, WritersProduceParseableFiles) {
  const GroundTruthTrajectory trajectory(shortDrive(1));
  const std::filesystem::path folder = std::filesystem::temp_directory_path() /
                                       ("lineloc_sensor_files_" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  const SiteProjection projection("UTM:31N", Eigen::Vector3d(593000.0, 5763000.0, 0.0));
  writeEurocImuCsv((folder / "imu.csv").string(), synthesiseImu(trajectory, ImuModel{}, 1));
  writeCompassCsv((folder / "compass.csv").string(),
                  synthesiseCompass(trajectory, CompassModel{}, 0.0, 1));
  writeNmeaFile((folder / "gps.nmea").string(), synthesiseGps(trajectory, GpsModel{}, 1),
                projection);
  std::ifstream nmea(folder / "gps.nmea");
  std::string line;
  int sentences = 0;
  while (std::getline(nmea, line)) {
    const NmeaStatus status = parseNmeaSentence(line).status;
    EXPECT_TRUE(status == NmeaStatus::kOk || status == NmeaStatus::kNoFix) << line;
    ++sentences;
  }
  EXPECT_EQ(sentences, 2 * 121);
  EXPECT_THROW(writeCompassCsv((folder / "missing" / "x.csv").string(), {}), std::runtime_error);
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace lineloc::sim
