#include "robot/inertial/restart_monitor.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "common/stats/chi_square.h"
#include "robot/inertial/robust_heading.h"

namespace lineloc {
namespace {

constexpr double kNsToS = 1e-9;
// Gated vision fixes that can show a common offset from the filter: three
// fit its offset and drift with a degree of freedom to spare.
constexpr size_t kMinGatedFixesForRestart = 3;
// Fraction of a run of gated compass readings that must agree on their offset
// from the filter's heading to restart it.
constexpr double kMinAgreeingCompassFraction = 0.9;

}  // namespace

std::optional<ResidualDrift> commonResidualDrift(const std::vector<GatedFix>& run, double gate) {
  const double n = static_cast<double>(run.size());
  std::vector<double> dt_s;
  Eigen::Vector3d position_mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d attitude_mean = Eigen::Vector3d::Zero();
  for (const GatedFix& gated : run) {
    dt_s.push_back(static_cast<double>(gated.stamp_ns - run.front().stamp_ns) * kNsToS);
    position_mean += gated.residual.head<3>() / n;
    attitude_mean += gated.residual.tail<3>() / n;
  }
  const double t_mean_s = std::accumulate(dt_s.begin(), dt_s.end(), 0.0) / n;
  double time_spread_s2 = 0.0;
  Eigen::Vector3d slope_sum = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < run.size(); ++i) {
    dt_s[i] -= t_mean_s;
    time_spread_s2 += dt_s[i] * dt_s[i];
    slope_sum += dt_s[i] * run[i].residual.head<3>();
  }
  ResidualDrift drift;
  drift.velocity_mps = slope_sum / time_spread_s2;
  drift.attitude_offset_rad = attitude_mean;
  double position_variance = 0.0;
  for (size_t i = 0; i < run.size(); ++i) {
    const Eigen::Vector3d position_error =
        run[i].residual.head<3>() - position_mean - dt_s[i] * drift.velocity_mps;
    const Eigen::Vector3d attitude_error = run[i].residual.tail<3>() - attitude_mean;
    const Matrix6d& fix_covariance = run[i].vision->T_world_camera.covariance;
    const Eigen::Matrix3d position_covariance = fix_covariance.topLeftCorner<3, 3>();
    const Eigen::Matrix3d attitude_covariance = fix_covariance.bottomRightCorner<3, 3>();
    if (position_error.dot(position_covariance.ldlt().solve(position_error)) > gate ||
        attitude_error.dot(attitude_covariance.ldlt().solve(attitude_error)) > gate) {
      return std::nullopt;
    }
    position_variance = std::max(position_variance, position_covariance.diagonal().maxCoeff());
  }
  drift.velocity_variance = position_variance / time_spread_s2;
  return drift;
}

VisionRestartMonitor::VisionRestartMonitor(const InertialNavigatorConfig& config)
    : restart_after_ns_(config.vision_gated_restart_after_ns),
      gate_(chiSquareQuantile(config.gate_probability, 3.0)),
      gravity_mps2_(config.gravity_mps2),
      T_body_camera_(config.T_body_camera) {}

std::vector<GatedFix> VisionRestartMonitor::gatedRun(const MeasurementHistory& history) const {
  const std::multimap<int64_t, Measurement>& measurements = history.measurements();
  std::vector<GatedFix> run;
  for (auto it = measurements.rbegin(); it != measurements.rend(); ++it) {
    const auto* vision = std::get_if<VisionPayload>(&it->second.payload);
    if (vision == nullptr || !it->second.outcome) {
      continue;
    }
    if (*it->second.outcome != MeasurementOutcome::kGated || !it->second.vision_residual) {
      return {};
    }
    run.push_back({it->first, vision, *it->second.vision_residual});
    if (run.front().stamp_ns - it->first >= restart_after_ns_) {
      return run;
    }
  }
  return {};
}

std::optional<VisionRestart> VisionRestartMonitor::restart(
    const MeasurementHistory& history) const {
  if (!history.started() || restart_after_ns_ <= 0) {
    return std::nullopt;
  }
  const std::vector<GatedFix> run = gatedRun(history);
  if (run.size() < kMinGatedFixesForRestart) {
    return std::nullopt;
  }
  const std::optional<ResidualDrift> drift = commonResidualDrift(run, gate_);
  if (!drift) {
    return std::nullopt;
  }
  const GatedFix& newest = run.front();
  const FilterSnapshot& filter = history.at(newest.stamp_ns);
  // The filter's velocity, corrected by the drift; its error also grows with
  // the attitude error the fixes show, g |theta| over half the run.
  const double run_s = static_cast<double>(newest.stamp_ns - run.back().stamp_ns) * kNsToS;
  const double tilt_velocity_sigma_mps =
      gravity_mps2_ * drift->attitude_offset_rad.norm() * 0.5 * run_s;
  const double velocity_variance =
      filter.covariance.block<3, 3>(kVelocity, kVelocity).diagonal().maxCoeff() +
      drift->velocity_variance + tilt_velocity_sigma_mps * tilt_velocity_sigma_mps;
  return VisionRestart{
      bodyFixOf(newest.stamp_ns, *newest.vision, T_body_camera_),
      StartVelocity{filter.state.v_world_body + drift->velocity_mps, std::sqrt(velocity_variance)}};
}

CompassRestartMonitor::CompassRestartMonitor(const InertialNavigatorConfig& config)
    : restart_after_ns_(config.compass_gated_restart_after_ns),
      gate_rad_(kCompassGateSigmas * config.compass_sigma_rad),
      yaw_sigma_rad_(compassYawSigma_rad(config)) {}

void CompassRestartMonitor::add(int64_t stamp_ns, const Measurement& measurement) {
  if (measurement.outcome != MeasurementOutcome::kAccepted &&
      measurement.outcome != MeasurementOutcome::kGated) {
    return;
  }
  const bool compass = measurement.kind() == MeasurementKind::kCompass;
  if (measurement.outcome == MeasurementOutcome::kGated && compass &&
      measurement.yaw_residual_rad) {
    gated_.push_back({stamp_ns, *measurement.yaw_residual_rad});
    return;
  }
  if (measurement.outcome == MeasurementOutcome::kAccepted &&
      (compass || measurement.kind() == MeasurementKind::kVision)) {
    gated_.clear();
  }
}

std::optional<NavigatorStart> CompassRestartMonitor::restart(const FilterSnapshot& latest) {
  if (restart_after_ns_ <= 0 || gated_.empty() ||
      gated_.back().stamp_ns - gated_.front().stamp_ns < restart_after_ns_) {
    return std::nullopt;
  }
  std::vector<double> residuals_rad;
  for (const GatedYaw& gated : gated_) {
    residuals_rad.push_back(gated.residual_rad);
  }
  const RobustHeading offset = robustCircularMean(residuals_rad, gate_rad_);
  if (offset.inliers < kMinAgreeingCompassFraction * static_cast<double>(residuals_rad.size())) {
    // A compass that wanders: the run slides on.
    gated_.erase(gated_.begin());
    return std::nullopt;
  }
  NavigatorStart start;
  start.state = latest.state;
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(offset.heading_rad, Eigen::Vector3d::UnitZ()));
  start.state.q_world_body = turn * start.state.q_world_body;
  start.state.v_world_body = turn * start.state.v_world_body;
  start.covariance = latest.covariance;
  start.covariance.row(kAttitude + 2).setZero();
  start.covariance.col(kAttitude + 2).setZero();
  start.covariance(kAttitude + 2, kAttitude + 2) = yaw_sigma_rad_ * yaw_sigma_rad_;
  start.imu = latest.imu;
  start.position = latest.position_known ? StartPosition::kFromSensors : StartPosition::kUnknown;
  start.unproven_covariance = latest.fixes.unproven_covariance;
  start.velocity_known = latest.velocity_known;
  return start;
}

}  // namespace lineloc
