// Test helper: drives an InertialNavigator through a simulated run, delivering
// camera fixes with a latency, optionally with an outage, and records the
// normalised errors against the truth.
#pragma once

#include <functional>
#include <optional>
#include <random>
#include <vector>

#include "robot/inertial/inertial_navigator.h"
#include "simulated_drive.h"

namespace lineloc::testing {

struct ScenarioConfig {
  uint64_t seed = 1;
  double duration_s = 60.0;
  int64_t fix_period_ns = 100'000'000;
  // Frames are exposed between IMU samples, so every fix splits an IMU interval.
  int64_t fix_phase_ns = 2'500'000;
  int64_t fix_latency_ns = 100'000'000;
  double fix_position_sigma_m = 0.03;
  double fix_rotation_sigma_rad = 0.1 * M_PI / 180.0;
  int64_t outage_start_ns = -1;  // relative to the drive's start; -1: none
  int64_t outage_length_ns = 0;
  int64_t record_period_ns = 1'000'000'000;
  // An offset drawn once from N(0, diag(sp^2, sr^2)) that every fix shares,
  // as fixes tracked from a search the backbone has not proven do; their
  // covariance includes it, stated as their unproven part when
  // `unproven_stated`, else left as noise on each.
  double unproven_position_sigma_m = 0.0;
  double unproven_rotation_sigma_rad = 0.0;
  bool unproven_stated = true;
};

struct Record {
  int64_t stamp_ns = 0;
  ErrorVector error = ErrorVector::Zero();
  ErrorCovariance covariance = ErrorCovariance::Identity();
  NavigatorHealth health;
  double nees() const { return error.dot(covariance.ldlt().solve(error)); }
  double positionNees() const {
    const Eigen::Vector3d e = error.segment<3>(kPosition);
    return e.dot(covariance.block<3, 3>(kPosition, kPosition).ldlt().solve(e));
  }
  // Of the tilt: the attitude error about the world's horizontal axes.
  double tiltNees() const {
    const Eigen::Vector2d e = error.segment<2>(kAttitude);
    return e.dot(covariance.block<2, 2>(kAttitude, kAttitude).ldlt().solve(e));
  }
};

struct ScenarioResult {
  std::vector<Record> records;
  std::vector<double> fix_nis;
  std::optional<NavigatorEstimate> final_estimate;
  NavigatorHealth final_health;
  Eigen::Vector3d unproven_position_offset_m = Eigen::Vector3d::Zero();
};

inline ErrorCovariance initialCovariance() {
  ErrorVector sigma;
  sigma << Eigen::Vector3d::Constant(0.1), Eigen::Vector3d::Constant(0.05), 0.01, 0.01, 0.02,
      Eigen::Vector3d::Constant(0.0035), Eigen::Vector3d::Constant(0.05);
  return sigma.cwiseAbs2().asDiagonal();
}

// NIS of a pose fix against the navigator's prediction for the same instant:
// r = [t_fix - t_pred; Log(R_fix R_pred^T)], S = Sigma_pred + Sigma_fix.
inline double poseFixNis(const PoseWithCovariance& predicted, const PoseWithCovariance& fix) {
  Eigen::Matrix<double, 6, 1> r;
  r.head<3>() = fix.pose.translation() - predicted.pose.translation();
  r.tail<3>() = logSO3(Eigen::Quaterniond(fix.pose.linear()) *
                       Eigen::Quaterniond(predicted.pose.linear()).conjugate());
  return r.dot((predicted.covariance + fix.covariance).ldlt().solve(r));
}

// The scenarios draw every fix's error anew, also at a standstill, and tell
// the navigator so.
inline InertialNavigatorConfig independentFixesConfig() {
  InertialNavigatorConfig config;
  config.vision_error_correlation_m = 0.0;
  config.shared_fix_error_fraction = 0.0;
  return config;
}

inline ScenarioResult runScenario(
    const ScenarioConfig& scenario,
    const InertialNavigatorConfig& config = independentFixesConfig()) {
  sim::TrajectoryConfig trajectory_config;
  trajectory_config.seed = scenario.seed;
  trajectory_config.duration_s = scenario.duration_s;
  trajectory_config.initial_still_s = 2.0;
  const sim::GroundTruthTrajectory trajectory(trajectory_config);
  const auto imu = sim::synthesiseImu(trajectory, sim::ImuModel{}, scenario.seed + 1000);
  std::mt19937_64 random(scenario.seed + 2000);

  InertialNavigator navigator(config);
  navigator.addImu(toImuSample(imu.front()));
  const ErrorCovariance P0 = initialCovariance();
  NavigationState start = truthState(trajectory, imu.front().stamp_ns);
  const Eigen::LLT<ErrorCovariance> llt(P0);
  std::normal_distribution<double> normal(0.0, 1.0);
  ErrorVector unit;
  for (int i = 0; i < kErrorStateSize; ++i) {
    unit(i) = normal(random);
  }
  ErrorVector initial_error = llt.matrixL() * unit;
  initial_error.tail<6>().setZero();  // the biases' error is the simulated turn-on bias
  injectError(-initial_error, start);
  navigator.initialise(start, P0);

  struct PendingFix {
    int64_t stamp_ns;
    PoseWithCovariance pose;
  };
  std::vector<PendingFix> pending;
  ScenarioResult result;
  const Matrix6d unproven = diagonalPoseCovariance(scenario.unproven_position_sigma_m,
                                                   scenario.unproven_rotation_sigma_rad);
  std::mt19937_64 offset_random(scenario.seed + 3000);
  const auto unitNormal3 = [&] {
    return Eigen::Vector3d(normal(offset_random), normal(offset_random), normal(offset_random));
  };
  result.unproven_position_offset_m = scenario.unproven_position_sigma_m * unitNormal3();
  const Eigen::Vector3d unproven_rotation_rad =
      scenario.unproven_rotation_sigma_rad * unitNormal3();
  const auto withUnprovenOffset = [&](PoseWithCovariance fix) {
    fix.pose.translation() += result.unproven_position_offset_m;
    fix.pose.linear() =
        (expSO3(unproven_rotation_rad) * Eigen::Quaterniond(fix.pose.linear())).toRotationMatrix();
    fix.covariance += unproven;
    return fix;
  };
  const int64_t t0 = imu.front().stamp_ns;
  int64_t next_frame = t0 + scenario.fix_phase_ns;
  int64_t next_record = t0 + scenario.record_period_ns;
  for (size_t i = 1; i < imu.size(); ++i) {
    const int64_t now = imu[i].stamp_ns;
    while (next_frame <= now) {
      const int64_t since_start = next_frame - t0;
      const bool in_outage = scenario.outage_start_ns >= 0 &&
                             since_start >= scenario.outage_start_ns &&
                             since_start < scenario.outage_start_ns + scenario.outage_length_ns;
      if (!in_outage) {
        pending.push_back({next_frame, withUnprovenOffset(noisyCameraFix(
                                           trajectory, next_frame, config.T_body_camera,
                                           scenario.fix_position_sigma_m,
                                           scenario.fix_rotation_sigma_rad, random))});
      }
      next_frame += scenario.fix_period_ns;
    }
    // Deliver the fixes whose latency has passed, before the IMU moves on.
    while (!pending.empty() && pending.front().stamp_ns + scenario.fix_latency_ns < now) {
      const PosePrediction predicted = navigator.predictAt(pending.front().stamp_ns);
      if (predicted.status == PredictionStatus::kOk) {
        result.fix_nis.push_back(poseFixNis(predicted.T_world_camera, pending.front().pose));
      }
      navigator.applyVisionFix(pending.front().stamp_ns, pending.front().pose,
                               scenario.unproven_stated ? unproven : Matrix6d::Zero());
      pending.erase(pending.begin());
    }
    navigator.addImu(toImuSample(imu[i]));
    if (now >= next_record) {
      const auto estimate = navigator.state();
      Record record;
      record.stamp_ns = now;
      record.error = errorBetween(truthState(trajectory, now, &imu[i]), estimate->state);
      record.covariance = estimate->covariance;
      record.health = navigator.health();
      result.records.push_back(record);
      next_record += scenario.record_period_ns;
    }
  }
  result.final_estimate = navigator.state();
  result.final_health = navigator.health();
  return result;
}

}  // namespace lineloc::testing
