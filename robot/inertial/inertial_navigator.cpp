#include "robot/inertial/inertial_navigator.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "common/stats/chi_square.h"
#include "robot/inertial/in_motion_alignment.h"
#include "robot/inertial/measurement_models.h"
#include "robot/inertial/robust_heading.h"

namespace lineloc {
namespace {

constexpr double kNsToS = 1e-9;
// Velocity sigma when starting still: a standing robot, but the IMU window
// cannot tell a creep of a few cm/s from standing.
constexpr double kStillVelocitySigma_mps = 0.05;
// Longest interval between two vision fixes whose difference starts the velocity.
constexpr int64_t kMaxVelocityBaseline_ns = 500'000'000;
// Bound on a ground robot's acceleration, for the error of that velocity.
constexpr double kMaxGroundAcceleration_mps2 = 2.0;
// Gated vision fixes that can show a common offset from the filter: three
// fit its offset and drift with a degree of freedom to spare.
constexpr size_t kMinGatedFixesForRestart = 3;
// Position sigma of a start without DGPS: unknown. A DGPS fix up to tens of
// kilometres from the site's origin passes the gate; in double precision a
// 1e8 m^2 variance rounds by 1e-8 m^2, a ten-thousandth of a vision fix's.
constexpr double kUnknownPositionSigma_m = 1e4;
// Compass readings needed for a start-up heading (1 s at 10 Hz).
constexpr size_t kMinStartupCompassReadings = 10;
// Start-up compass readings farther than this many compass sigmas from their
// circular median are disturbed and left out of the heading (robust_heading.h).
constexpr double kStartupHeadingGateSigmas = 3.0;
// Fraction of a run of gated compass readings that must agree on their offset
// from the filter's heading to restart it.
constexpr double kMinAgreeingCompassFraction = 0.9;
// Bound on a correlated fix's covariance inflation: a fix of an unchanged view
// still counts, at a ten-thousandth of an independent one.
constexpr double kMaxCorrelatedFixInflation = 1e4;
// Longest interval between the two DGPS velocities of a start in motion (two
// epochs of a 1 Hz receiver, with jitter); longer, the tilt is as good but the
// robot's turns between them are the gyros' to carry.
constexpr int64_t kMaxVelocityMatchingBaseline_ns = 1'500'000'000;
// A DGPS velocity faster than this many of its sigmas (per axis) is motion.
constexpr double kMovingSpeedSigmas = 4.0;
// A DGPS fix this close to a start in motion's last velocity is of its epoch.
constexpr int64_t kSameEpoch_ns = 50'000'000;
// Vertical velocity of a start in motion, per m/s of horizontal speed: a
// steep street's grade (8 %).
constexpr double kSteepGrade = 0.08;

void requirePositive(double value, const char* name) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(
        fmt::format("inertial navigator: {} must be > 0, got {}", name, value));
  }
}

void requireNonNegative(double value, const char* name) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(
        fmt::format("inertial navigator: {} must be >= 0, got {}", name, value));
  }
}

bool isPositiveDefinite(const Matrix6d& covariance) {
  return covariance.isApprox(covariance.transpose(), 1e-9) &&
         Eigen::LLT<Matrix6d>(covariance).info() == Eigen::Success;
}

// A fix's unproven part: symmetric, no negative variance, and within the fix's
// covariance, what is left of it positive definite.
bool isUnprovenPartOf(const Matrix6d& unproven, const Matrix6d& covariance) {
  return unproven.allFinite() && unproven.isApprox(unproven.transpose(), 1e-9) &&
         Eigen::SelfAdjointEigenSolver<Matrix6d>(unproven, Eigen::EigenvaluesOnly)
                 .eigenvalues()
                 .minCoeff() >= 0.0 &&
         isPositiveDefinite(covariance - unproven);
}

MeasurementOutcome fromUpdate(UpdateStatus status) {
  switch (status) {
    case UpdateStatus::kAccepted:
      return MeasurementOutcome::kAccepted;
    case UpdateStatus::kGated:
      return MeasurementOutcome::kGated;
    case UpdateStatus::kDegenerate:
      return MeasurementOutcome::kDegenerate;
  }
  return MeasurementOutcome::kDegenerate;
}

int64_t& counterOf(MeasurementCounters& counters, MeasurementOutcome outcome) {
  switch (outcome) {
    case MeasurementOutcome::kAccepted:
      return counters.accepted;
    case MeasurementOutcome::kGated:
      return counters.gated;
    case MeasurementOutcome::kDegenerate:
      return counters.degenerate;
    case MeasurementOutcome::kSkipped:
      return counters.skipped;
    case MeasurementOutcome::kTooLate:
      return counters.too_late;
    case MeasurementOutcome::kInvalid:
      return counters.invalid;
    case MeasurementOutcome::kPending:
      break;
  }
  throw std::logic_error("a pending measurement has no counter");
}

// The part of a fix's covariance (camera pose error [dp; dtheta], dtheta in
// the world frame) the filter takes as an offset of the fixes' frame (the
// unproven part, the error the fixes share): all but the tilt (rotation about
// the world's horizontal axes), which gravity makes observable to the
// accelerometers and which stays noise on each fix.
Matrix6d levelFrameOffset(Matrix6d covariance) {
  for (const int tilt_axis : {3, 4}) {
    covariance.row(tilt_axis).setZero();
    covariance.col(tilt_axis).setZero();
  }
  return covariance;
}

// The covariance the filter reports: its own, of the pose relative to the
// fixes' frame, plus the unproven offset of that frame, covering the share of
// the last applied fix's covariance its error keeps over metres (body pose
// error [dp; dtheta], both; see the header). Raising a principal block by a
// positive semi-definite amount keeps the whole positive semi-definite. A
// singular pose block (a state started as exactly known) has no covering; the
// sum, though looser, covers both.
ErrorCovariance reportedCovariance(ErrorCovariance covariance, const Matrix6d& unproven_body,
                                   const Matrix6d& fix_offset_body) {
  const Matrix6d pose = poseBlock(covariance) + unproven_body;
  const Matrix6d covering = coveringCovariance(pose, fix_offset_body);
  setPoseBlock(covering.allFinite() ? covering : pose + fix_offset_body, covariance);
  return covariance;
}

Eigen::Quaterniond quaternionFromYawPitchRoll(double yaw, double pitch, double roll) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
}

}  // namespace

Eigen::Isometry3d InertialNavigatorConfig::defaultBodyCamera() {
  Eigen::Isometry3d T_body_camera = Eigen::Isometry3d::Identity();
  T_body_camera.linear() << 0.0, 0.0, 1.0, -1.0, 0.0, 0.0, 0.0, -1.0, 0.0;
  return T_body_camera;
}

const char* toString(NavigatorMode mode) {
  switch (mode) {
    case NavigatorMode::kInitialising:
      return "initialising";
    case NavigatorMode::kTracking:
      return "tracking";
    case NavigatorMode::kDeadReckoning:
      return "dead reckoning";
    case NavigatorMode::kLost:
      return "lost";
  }
  return "unknown";
}

InertialNavigator::InertialNavigator(const InertialNavigatorConfig& config)
    : config_(config),
      strapdown_(config.imu_noise, Eigen::Vector3d(0.0, 0.0, -config.gravity_mps2)),
      alignment_detector_(config.alignment),
      zero_velocity_detector_(config.zero_velocity) {
  requirePositive(config.gravity_mps2, "gravity_mps2");
  requirePositive(config.gyro_range_radps, "gyro_range_radps");
  requirePositive(config.accel_range_mps2, "accel_range_mps2");
  requirePositive(static_cast<double>(config.history_ns), "history_ns");
  requirePositive(config.gps_horizontal_sigma_m, "gps_horizontal_sigma_m");
  requirePositive(config.gps_vertical_sigma_m, "gps_vertical_sigma_m");
  requirePositive(config.max_ground_speed_mps, "max_ground_speed_mps");
  requirePositive(config.gps_velocity_sigma_mps, "gps_velocity_sigma_mps");
  requirePositive(config.compass_sigma_rad, "compass_sigma_rad");
  requireNonNegative(config.compass_bias_sigma_rad, "compass_bias_sigma_rad");
  requirePositive(config.zero_velocity_sigma_mps, "zero_velocity_sigma_mps");
  if (config.vision_error_correlation_m != 0.0) {
    requirePositive(config.vision_error_correlation_m, "vision_error_correlation_m");
    requirePositive(config.vision_error_correlation_rad, "vision_error_correlation_rad");
  }
  if (config.shared_fix_error_length_m != 0.0) {
    requirePositive(config.shared_fix_error_length_m, "shared_fix_error_length_m");
  }
  if (!config.R_body_imu.isUnitary(1e-6) || config.R_body_imu.determinant() < 0.0) {
    throw std::invalid_argument("inertial navigator: R_body_imu is not a rotation");
  }
  if (!(config.shared_fix_error_fraction >= 0.0 && config.shared_fix_error_fraction <= 1.0)) {
    throw std::invalid_argument(
        fmt::format("inertial navigator: shared_fix_error_fraction must be in [0, 1], got {}",
                    config.shared_fix_error_fraction));
  }
  if (!(config.gate_probability > 0.0 && config.gate_probability < 1.0)) {
    throw std::invalid_argument(fmt::format(
        "inertial navigator: gate_probability must be in (0, 1), got {}", config.gate_probability));
  }
  for (size_t dimension = 1; dimension < gate_by_dimension_.size(); ++dimension) {
    gate_by_dimension_[dimension] =
        chiSquareQuantile(config.gate_probability, static_cast<double>(dimension));
  }
}

bool InertialNavigator::acceptImu(const ImuSample& sample) {
  ImuCounters& counters = counters_.imu;
  if (!sample.gyro_radps.allFinite() || !sample.accel_mps2.allFinite()) {
    ++counters.non_finite;
    return false;
  }
  if (sample.gyro_radps.cwiseAbs().maxCoeff() >= config_.gyro_range_radps ||
      sample.accel_mps2.cwiseAbs().maxCoeff() >= config_.accel_range_mps2) {
    ++counters.saturated;
    return false;
  }
  if (last_imu_stamp_ns_ && sample.stamp_ns <= *last_imu_stamp_ns_) {
    ++(sample.stamp_ns == *last_imu_stamp_ns_ ? counters.duplicate : counters.out_of_order);
    return false;
  }
  if (last_imu_stamp_ns_ && sample.stamp_ns - *last_imu_stamp_ns_ > config_.imu_gap_ns) {
    ++counters.gaps;
  }
  ++counters.accepted;
  last_imu_stamp_ns_ = sample.stamp_ns;
  return true;
}

void InertialNavigator::addImu(const ImuSample& sample_imu) {
  const ImuSample sample{sample_imu.stamp_ns, config_.R_body_imu * sample_imu.gyro_radps,
                         config_.R_body_imu * sample_imu.accel_mps2};
  if (!acceptImu(sample)) {
    return;
  }
  zero_velocity_detector_.add(sample);
  imu_.push_back({sample, zero_velocity_detector_.isStill()});
  if (snapshots_.empty()) {
    alignment_detector_.add(sample);
    moved_since_start_ = moved_since_start_ || alignment_detector_.isMoving();
    if (auto alignment = alignment_detector_.alignment()) {
      alignment_ = alignment;
    }
    tryInitialiseFromSensors();
    tryInitialiseInMotion();
  } else {
    process(imu_.back());
    restartIfVisionKeepsBeingGated();
  }
  prune();
  restartHeadingIfCompassKeepsBeingGated();
}

void InertialNavigator::addGps(const GpsFix& fix) {
  if (!fix.p_world_antenna.allFinite()) {
    ++counters_.gps.invalid;
    return;
  }
  if (snapshots_.empty()) {
    startup_gps_ = fix;
    tryInitialiseFromSensors();
    return;
  }
  addMeasurement(fix.stamp_ns,
                 {GpsPayload{fix.p_world_antenna}, std::nullopt, std::nullopt, std::nullopt});
}

void InertialNavigator::addGpsVelocity(const GpsVelocity& velocity) {
  if (!velocity.v_world_mps.allFinite()) {
    ++counters_.gps_velocity.invalid;
    return;
  }
  if (!snapshots_.empty()) {
    addMeasurement(velocity.stamp_ns, {GpsVelocityPayload{velocity.v_world_mps}, std::nullopt,
                                       std::nullopt, std::nullopt});
    return;
  }
  // A robot cruising on a smooth road can look as still to the IMU as a
  // standing one; a speed the receiver measures beyond its noise on two
  // consecutive epochs is motion, one the next epoch denies multipath.
  const bool claimed = motionClaimed();
  if (isMotion(velocity)) {
    moved_since_start_ = moved_since_start_ || claimed;
  } else if (claimed) {
    ++counters_.gps_velocity.gated;
  }
  startup_velocities_.push_back(velocity);
  if (startup_velocities_.size() > 2) {
    startup_velocities_.pop_front();
  }
  tryInitialiseInMotion();
}

bool InertialNavigator::isMotion(const GpsVelocity& velocity) const {
  return velocity.v_world_mps.norm() > kMovingSpeedSigmas * config_.gps_velocity_sigma_mps;
}

bool InertialNavigator::motionClaimed() const {
  return !startup_velocities_.empty() && isMotion(startup_velocities_.back());
}

bool InertialNavigator::mayHaveMoved() const {
  return moved_since_start_ || motionClaimed();
}

void InertialNavigator::addCompass(const CompassReading& reading) {
  if (!std::isfinite(reading.magnetic_heading_rad)) {
    ++counters_.compass.invalid;
    return;
  }
  if (snapshots_.empty()) {
    startup_compass_.push_back(reading);
    tryInitialiseFromSensors();
    return;
  }
  addMeasurement(reading.stamp_ns, {YawPayload{yawFromCompass(reading.magnetic_heading_rad)},
                                    std::nullopt, std::nullopt, std::nullopt});
}

MeasurementOutcome InertialNavigator::applyVisionFix(int64_t stamp_ns,
                                                     const PoseWithCovariance& T_world_camera,
                                                     const Matrix6d& unproven_covariance) {
  if (!isFinitePose(T_world_camera) || !isPositiveDefinite(T_world_camera.covariance) ||
      !isUnprovenPartOf(unproven_covariance, T_world_camera.covariance)) {
    ++counters_.vision.invalid;
    return MeasurementOutcome::kInvalid;
  }
  const VisionPayload vision{T_world_camera, levelFrameOffset(unproven_covariance)};
  if (snapshots_.empty()) {
    const BodyFix fix = bodyFixOf(stamp_ns, vision);
    const std::optional<StartVelocity> velocity = startVelocity(fix, startup_vision_);
    const MeasurementOutcome outcome =
        velocity ? startFromVision(fix, *velocity) : MeasurementOutcome::kSkipped;
    startup_vision_ = fix;
    ++counterOf(counters_.vision, outcome);
    return outcome;
  }
  const MeasurementOutcome outcome =
      addMeasurement(stamp_ns, {vision, std::nullopt, std::nullopt, std::nullopt});
  restartIfVisionKeepsBeingGated();
  return outcome;
}

MeasurementOutcome InertialNavigator::addMeasurement(int64_t stamp_ns, Measurement measurement) {
  if (stamp_ns <= snapshots_.front().state.stamp_ns) {
    ++countersFor(measurement).too_late;
    return MeasurementOutcome::kTooLate;
  }
  const auto inserted = measurements_.emplace(stamp_ns, std::move(measurement));
  const auto after = std::lower_bound(
      snapshots_.begin(), snapshots_.end(), stamp_ns,
      [](const Snapshot& snapshot, int64_t stamp) { return snapshot.state.stamp_ns < stamp; });
  if (after != snapshots_.end()) {
    replayFrom(static_cast<size_t>(after - snapshots_.begin()) - 1);
  }
  return inserted->second.outcome.value_or(MeasurementOutcome::kPending);
}

void InertialNavigator::replayFrom(size_t snapshot_index) {
  snapshots_.erase(snapshots_.begin() + static_cast<std::ptrdiff_t>(snapshot_index) + 1,
                   snapshots_.end());
  const int64_t from_ns = snapshots_.back().state.stamp_ns;
  auto next = std::upper_bound(
      imu_.begin(), imu_.end(), from_ns,
      [](int64_t stamp, const BufferedImu& imu) { return stamp < imu.sample.stamp_ns; });
  for (; next != imu_.end(); ++next) {
    process(*next);
  }
}

void InertialNavigator::process(const BufferedImu& imu) {
  Snapshot snapshot = snapshots_.back();
  const ImuSample start = snapshot.imu;
  ImuSample current = start;
  const auto end = measurements_.upper_bound(imu.sample.stamp_ns);
  for (auto it = measurements_.upper_bound(start.stamp_ns); it != end; ++it) {
    const ImuSample at_measurement = interpolateImu(start, imu.sample, it->first);
    propagate(current, at_measurement, snapshot);
    current = at_measurement;
    recordOutcome(it->second, apply(it->second, at_measurement, snapshot));
  }
  if (imu.sample.stamp_ns > current.stamp_ns) {
    propagate(current, imu.sample, snapshot);
  }
  const bool slow = snapshot.state.v_world_body.norm() < config_.zero_velocity_max_speed_mps;
  if (imu.still && slow && snapshot.velocity_known &&
      imu.sample.stamp_ns - snapshot.last_zero_velocity_ns >= config_.zero_velocity_interval_ns) {
    const UpdateOutcome outcome =
        applyUpdate(lineariseZeroVelocity(snapshot.state, config_.zero_velocity_sigma_mps),
                    gate_by_dimension_[3], snapshot.state, snapshot.covariance);
    if (outcome.status == UpdateStatus::kAccepted) {
      snapshot.last_zero_velocity_ns = imu.sample.stamp_ns;
      ++snapshot.zero_velocity_updates;
    }
  }
  snapshot.imu = imu.sample;
  snapshots_.push_back(std::move(snapshot));
}

void InertialNavigator::propagate(const ImuSample& from, const ImuSample& to,
                                  Snapshot& snapshot) const {
  const Eigen::Vector3d p_before = snapshot.state.p_world_body;
  strapdown_.propagate(from, to, snapshot.state, snapshot.covariance);
  if (config_.shared_fix_error_length_m == 0.0 || !snapshot.at_last_vision) {
    return;
  }
  // rho^2 = exp(-2 d / L_s) at the distance d from the last applied fix.
  const auto correlationSquared = [&](const Eigen::Vector3d& p_world_body) {
    return std::exp(-2.0 * (p_world_body - snapshot.at_last_vision->p_world_body).norm() /
                    config_.shared_fix_error_length_m);
  };
  const double decorrelated =
      std::max(0.0, correlationSquared(p_before) - correlationSquared(snapshot.state.p_world_body));
  setPoseBlock(poseBlock(snapshot.covariance) + decorrelated * snapshot.shared_fix_error,
               snapshot.covariance);
}

MeasurementOutcome InertialNavigator::apply(Measurement& measurement, const ImuSample& imu,
                                            Snapshot& snapshot) const {
  NavigationState& state = snapshot.state;
  ErrorCovariance& covariance = snapshot.covariance;
  if (const auto* vision = std::get_if<VisionPayload>(&measurement.payload)) {
    const LinearisedMeasurement<6> z =
        linearisePoseFix(state, vision->T_world_camera, config_.T_body_camera);
    measurement.vision_residual = z.residual;
    const Matrix6d update_noise =
        correlatedFixInflation(snapshot) * (z.noise - vision->unproven_covariance);
    const double prior_position_variance = covariance.block<3, 3>(kPosition, kPosition).trace();
    const UpdateOutcome outcome =
        applyUpdate(z, gate_by_dimension_[6], state, covariance, update_noise);
    if (outcome.status == UpdateStatus::kAccepted) {
      snapshot.position_known = true;
      snapshot.velocity_known = true;
      snapshot.at_last_vision = state;
      snapshot.unproven_covariance =
          bodyCovarianceOf(vision->T_world_camera.pose, vision->unproven_covariance);
      snapshot.fix_offset_covariance =
          config_.shared_fix_error_fraction *
          bodyCovarianceOf(vision->T_world_camera.pose, vision->T_world_camera.covariance);
      // The fix's share w of the state: the part of its position variance
      // the update took out.
      const double share =
          prior_position_variance > 0.0
              ? std::clamp(1.0 - covariance.block<3, 3>(kPosition, kPosition).trace() /
                                     prior_position_variance,
                           0.0, 1.0)
              : 0.0;
      snapshot.shared_fix_error =
          (1.0 - share) * snapshot.shared_fix_error +
          share * config_.shared_fix_error_fraction *
              bodyCovarianceOf(vision->T_world_camera.pose,
                               levelFrameOffset(z.noise - vision->unproven_covariance));
    }
    return fromUpdate(outcome.status);
  }
  if (const auto* gps = std::get_if<GpsPayload>(&measurement.payload)) {
    const double gps_variance = config_.gps_horizontal_sigma_m * config_.gps_horizontal_sigma_m;
    const Eigen::Matrix3d noise =
        Eigen::Vector3d(gps_variance, gps_variance,
                        config_.gps_vertical_sigma_m * config_.gps_vertical_sigma_m)
            .asDiagonal();
    const std::optional<UpdateOutcome> outcome = applyBoundingUpdate(
        lineariseAntennaPosition(state, gps->p_world_antenna, noise, config_.p_body_gps_antenna),
        gate_by_dimension_[3], state, covariance);
    if (outcome && outcome->status == UpdateStatus::kAccepted) {
      snapshot.position_known = true;
    }
    return outcome ? fromUpdate(outcome->status) : MeasurementOutcome::kSkipped;
  }
  if (const auto* velocity = std::get_if<GpsVelocityPayload>(&measurement.payload)) {
    const UpdateOutcome outcome = applyUpdate(
        lineariseAntennaVelocity(state, imu.gyro_radps, velocity->v_world_antenna_mps,
                                 config_.gps_velocity_sigma_mps, config_.p_body_gps_antenna),
        gate_by_dimension_[2], state, covariance);
    if (outcome.status == UpdateStatus::kAccepted) {
      snapshot.velocity_known = true;
    }
    return fromUpdate(outcome.status);
  }
  const auto& yaw = std::get<YawPayload>(measurement.payload);
  const auto z = lineariseYaw(state, yaw.yaw_rad, compassYawSigma_rad());
  if (!z) {
    return MeasurementOutcome::kDegenerate;
  }
  measurement.yaw_residual_rad = z->residual(0);
  const std::optional<UpdateOutcome> outcome =
      applyBoundingUpdate(*z, gate_by_dimension_[1], state, covariance);
  return outcome ? fromUpdate(outcome->status) : MeasurementOutcome::kSkipped;
}

double InertialNavigator::correlatedFixInflation(const Snapshot& snapshot) const {
  if (!snapshot.at_last_vision || config_.vision_error_correlation_m == 0.0) {
    return 1.0;
  }
  const NavigationState& last = *snapshot.at_last_vision;
  const double travel_m = (snapshot.state.p_world_body - last.p_world_body).norm();
  const double turn_rad = snapshot.state.q_world_body.angularDistance(last.q_world_body);
  const double rho = std::exp(-(travel_m / config_.vision_error_correlation_m +
                                turn_rad / config_.vision_error_correlation_rad));
  return std::min((1.0 + rho) / (1.0 - rho), kMaxCorrelatedFixInflation);
}

MeasurementCounters& InertialNavigator::countersFor(const Measurement& measurement) {
  if (std::holds_alternative<VisionPayload>(measurement.payload)) {
    return counters_.vision;
  }
  if (std::holds_alternative<GpsVelocityPayload>(measurement.payload)) {
    return counters_.gps_velocity;
  }
  return std::holds_alternative<GpsPayload>(measurement.payload) ? counters_.gps
                                                                 : counters_.compass;
}

void InertialNavigator::recordOutcome(Measurement& measurement, MeasurementOutcome outcome) {
  if (measurement.outcome == outcome) {
    return;
  }
  MeasurementCounters& counters = countersFor(measurement);
  if (measurement.outcome) {
    --counterOf(counters, *measurement.outcome);
  }
  ++counterOf(counters, outcome);
  measurement.outcome = outcome;
}

void InertialNavigator::prune() {
  const int64_t keep_from_ns = imu_.back().sample.stamp_ns - config_.history_ns;
  while (snapshots_.size() > 1 && snapshots_[1].state.stamp_ns <= keep_from_ns) {
    snapshots_.pop_front();
  }
  const int64_t first_ns = snapshots_.empty() ? keep_from_ns : snapshots_.front().state.stamp_ns;
  // Keep one sample at or before the first snapshot, for interpolation.
  while (imu_.size() > 1 && imu_[1].sample.stamp_ns <= first_ns) {
    imu_.pop_front();
  }
  const auto kept = measurements_.upper_bound(first_ns);
  for (auto it = measurements_.begin(); it != kept; ++it) {
    trackGatedCompass(it->first, it->second);
  }
  measurements_.erase(measurements_.begin(), kept);
  // Start-up heading: the compass readings of the last still window.
  const int64_t compass_from_ns = imu_.back().sample.stamp_ns - config_.alignment.window_ns;
  while (!startup_compass_.empty() && startup_compass_.front().stamp_ns < compass_from_ns) {
    startup_compass_.pop_front();
  }
}

std::optional<ImuSample> InertialNavigator::bufferedImuAt(int64_t stamp_ns) const {
  return imuAt(imu_.begin(), imu_.end(), stamp_ns, &InertialNavigator::sampleOf);
}

bool InertialNavigator::initialise(const NavigationState& state,
                                   const ErrorCovariance& covariance) {
  const auto imu = bufferedImuAt(state.stamp_ns);
  if (!imu) {
    return false;
  }
  startAt(state, covariance, *imu, StartPosition::kFromSensors);
  return true;
}

void InertialNavigator::startAt(const NavigationState& state, const ErrorCovariance& covariance,
                                const ImuSample& imu, StartPosition position,
                                const Matrix6d& unproven_covariance, bool velocity_known) {
  snapshots_.clear();
  measurements_.clear();
  Snapshot snapshot;
  snapshot.state = state;
  snapshot.covariance = covariance;
  snapshot.imu = imu;
  snapshot.last_zero_velocity_ns = state.stamp_ns;
  snapshot.unproven_covariance = unproven_covariance;
  snapshot.position_known = position != StartPosition::kUnknown;
  snapshot.velocity_known = velocity_known;
  if (position == StartPosition::kFromVision) {
    snapshot.at_last_vision = state;
  }
  snapshots_.push_back(snapshot);
  startup_gps_.reset();
  startup_velocities_.clear();
  startup_compass_.clear();
  gated_compass_.clear();
  startup_vision_.reset();
  replayFrom(0);
}

Eigen::Vector3d InertialNavigator::initialGyroBias(bool stood_still, double& sigma_radps) const {
  if (!alignment_ || !stood_still) {
    sigma_radps = config_.gyro_turn_on_bias_sigma_radps;
    return Eigen::Vector3d::Zero();
  }
  // Mean of white rate noise over T seconds: sigma^2 = N^2 / T.
  sigma_radps = config_.imu_noise.gyro_noise_radps_per_sqrt_hz / std::sqrt(alignment_->duration_s);
  return alignment_->gyro_bias_radps;
}

double InertialNavigator::compassYawSigma_rad() const {
  return std::hypot(config_.compass_sigma_rad, config_.compass_bias_sigma_rad);
}

double InertialNavigator::yawFromCompass(double magnetic_heading_rad) const {
  // Grid bearing = magnetic + declination + grid bearing of true north; the
  // world yaw is anticlockwise from east: yaw = pi/2 - grid bearing.
  return wrapAngle(M_PI_2 - (magnetic_heading_rad + config_.magnetic_declination_rad +
                             config_.grid_bearing_of_true_north_rad));
}

void InertialNavigator::tryInitialiseFromSensors() {
  // Only while standing still since power-on: the start covariance assumes it,
  // and a robot cruising on a smooth road can be as quiet as a standing one.
  const auto alignment = alignment_detector_.alignment();
  if (mayHaveMoved() || !alignment || startup_compass_.size() < kMinStartupCompassReadings) {
    return;
  }
  std::vector<double> compass_yaws_rad;
  for (const CompassReading& reading : startup_compass_) {
    compass_yaws_rad.push_back(yawFromCompass(reading.magnetic_heading_rad));
  }
  const double yaw_rad =
      robustCircularMean(compass_yaws_rad, kStartupHeadingGateSigmas * config_.compass_sigma_rad)
          .heading_rad;
  const ImuSample& latest = imu_.back().sample;
  NavigationState state;
  state.stamp_ns = latest.stamp_ns;
  state.q_world_body =
      quaternionFromYawPitchRoll(yaw_rad, alignment->pitch_rad, alignment->roll_rad);
  // Without DGPS only the IMU says the robot stands (see the header): the
  // velocity is unknown, and the window's mean rate may be the body pitching.
  const bool with_dgps = startup_gps_.has_value();
  const Eigen::Vector3d position_sigma_m = placeAtDgps(with_dgps ? &*startup_gps_ : nullptr, state);
  double gyro_bias_sigma = 0.0;
  state.gyro_bias_radps = initialGyroBias(with_dgps, gyro_bias_sigma);
  // A tilt error of b_a / g hides behind an accelerometer bias b_a.
  const double tilt_sigma = config_.accel_turn_on_bias_sigma_mps2 / config_.gravity_mps2;
  const double velocity_sigma_mps =
      with_dgps ? kStillVelocitySigma_mps : config_.max_ground_speed_mps;
  ErrorVector sigma;
  sigma << position_sigma_m, Eigen::Vector3d::Constant(velocity_sigma_mps), tilt_sigma, tilt_sigma,
      compassYawSigma_rad(), Eigen::Vector3d::Constant(gyro_bias_sigma),
      Eigen::Vector3d::Constant(config_.accel_turn_on_bias_sigma_mps2);
  startAt(state, sigma.cwiseAbs2().asDiagonal(), latest,
          with_dgps ? StartPosition::kFromSensors : StartPosition::kUnknown, Matrix6d::Zero(),
          with_dgps);
}

Eigen::Vector3d InertialNavigator::placeAtDgps(const GpsFix* fix, NavigationState& state) const {
  if (fix == nullptr) {
    return Eigen::Vector3d::Constant(kUnknownPositionSigma_m);
  }
  state.p_world_body = fix->p_world_antenna - state.q_world_body * config_.p_body_gps_antenna;
  return {config_.gps_horizontal_sigma_m, config_.gps_horizontal_sigma_m,
          config_.gps_vertical_sigma_m};
}

void InertialNavigator::tryInitialiseInMotion() {
  // Only once the robot has moved since power-on: standing, the start above
  // levels better. Tried once per pair of velocities, when the IMU has passed
  // the second (and the DGPS fix of its epoch has come).
  if (!snapshots_.empty() || !moved_since_start_ || startup_velocities_.size() < 2 ||
      imu_.back().sample.stamp_ns <= startup_velocities_.back().stamp_ns) {
    return;
  }
  const GpsVelocity from = startup_velocities_.front();
  const GpsVelocity to = startup_velocities_.back();
  startup_velocities_.pop_front();
  if (to.stamp_ns - from.stamp_ns > kMaxVelocityMatchingBaseline_ns) {
    return;
  }
  const std::optional<std::vector<ImuSample>> imu =
      imuOver(imu_.begin(), imu_.end(), from.stamp_ns, to.stamp_ns, &InertialNavigator::sampleOf);
  if (!imu) {
    return;
  }
  std::vector<TimedYaw> compass_yaws;
  for (const CompassReading& reading : startup_compass_) {
    compass_yaws.push_back({reading.stamp_ns, yawFromCompass(reading.magnetic_heading_rad)});
  }
  const InMotionAlignmentNoise noise{
      config_.gravity_mps2, config_.gps_velocity_sigma_mps, config_.accel_turn_on_bias_sigma_mps2,
      config_.gyro_turn_on_bias_sigma_radps, kStartupHeadingGateSigmas * config_.compass_sigma_rad};
  const std::optional<InMotionAttitude> attitude = alignInMotion(
      *imu, from.stamp_ns, from.v_world_mps, to.stamp_ns, to.v_world_mps, compass_yaws, noise);
  if (!attitude) {
    return;
  }
  const ImuSample& imu_at_start = imu->back();
  NavigationState state;
  state.stamp_ns = to.stamp_ns;
  state.q_world_body = attitude->q_world_body;
  // v_body = v_antenna - R (omega x r).
  state.v_world_body =
      Eigen::Vector3d(to.v_world_mps.x(), to.v_world_mps.y(), 0.0) -
      state.q_world_body * imu_at_start.gyro_radps.cross(config_.p_body_gps_antenna);
  const bool position_known =
      startup_gps_ && std::abs(startup_gps_->stamp_ns - to.stamp_ns) <= kSameEpoch_ns;
  const Eigen::Vector3d position_sigma_m =
      placeAtDgps(position_known ? &*startup_gps_ : nullptr, state);
  double gyro_bias_sigma = 0.0;
  state.gyro_bias_radps = initialGyroBias(false, gyro_bias_sigma);
  const double vertical_velocity_sigma =
      std::max(kStillVelocitySigma_mps, kSteepGrade * to.v_world_mps.norm());
  ErrorVector sigma;
  sigma << position_sigma_m, config_.gps_velocity_sigma_mps, config_.gps_velocity_sigma_mps,
      vertical_velocity_sigma, attitude->tilt_sigma_rad, attitude->tilt_sigma_rad,
      compassYawSigma_rad(), Eigen::Vector3d::Constant(gyro_bias_sigma),
      Eigen::Vector3d::Constant(config_.accel_turn_on_bias_sigma_mps2);
  counters_.gps_velocity.accepted += 2;
  startAt(state, sigma.cwiseAbs2().asDiagonal(), imu_at_start,
          position_known ? StartPosition::kFromSensors : StartPosition::kUnknown);
}

InertialNavigator::BodyFix InertialNavigator::bodyFixOf(int64_t stamp_ns,
                                                        const VisionPayload& vision) const {
  const Eigen::Isometry3d& T_world_camera = vision.T_world_camera.pose;
  return {stamp_ns, T_world_camera * config_.T_body_camera.inverse(),
          bodyCovarianceOf(T_world_camera,
                           vision.T_world_camera.covariance - vision.unproven_covariance),
          bodyCovarianceOf(T_world_camera, vision.unproven_covariance)};
}

Matrix6d InertialNavigator::bodyCovarianceOf(const Eigen::Isometry3d& T_world_camera,
                                             const Matrix6d& camera_covariance) const {
  // The camera's pose moved by the exact camera -> body transform: the inverse
  // of the lever-arm Jacobian of cameraPoseOf().
  return composeExactMotion({T_world_camera, camera_covariance}, config_.T_body_camera.inverse())
      .covariance;
}

std::optional<InertialNavigator::StartVelocity> InertialNavigator::startVelocity(
    const BodyFix& fix, const std::optional<BodyFix>& previous) const {
  if (!mayHaveMoved() && alignment_detector_.isStill()) {
    return StartVelocity{Eigen::Vector3d::Zero(), kStillVelocitySigma_mps};
  }
  const int64_t baseline_ns = previous ? fix.stamp_ns - previous->stamp_ns : 0;
  if (baseline_ns <= 0 || baseline_ns > kMaxVelocityBaseline_ns) {
    return std::nullopt;
  }
  // v = dp / dt; sigma from both positions, plus the speed change a dt / 2
  // the mean velocity misses at a ground robot's acceleration.
  const double dt = static_cast<double>(baseline_ns) * kNsToS;
  const double position_variance = fix.covariance.topLeftCorner<3, 3>().diagonal().maxCoeff() +
                                   previous->covariance.topLeftCorner<3, 3>().diagonal().maxCoeff();
  return StartVelocity{(fix.T_world_body.translation() - previous->T_world_body.translation()) / dt,
                       std::sqrt(position_variance) / dt + 0.5 * kMaxGroundAcceleration_mps2 * dt};
}

MeasurementOutcome InertialNavigator::startFromVision(const BodyFix& fix,
                                                      const StartVelocity& velocity) {
  const auto imu = bufferedImuAt(fix.stamp_ns);
  if (!imu) {
    return MeasurementOutcome::kTooLate;
  }
  NavigationState state;
  state.stamp_ns = fix.stamp_ns;
  state.p_world_body = fix.T_world_body.translation();
  state.q_world_body = Eigen::Quaterniond(fix.T_world_body.linear()).normalized();
  state.v_world_body = velocity.v_world_mps;
  double gyro_bias_sigma = 0.0;
  state.gyro_bias_radps = initialGyroBias(!mayHaveMoved(), gyro_bias_sigma);
  ErrorCovariance covariance = ErrorCovariance::Zero();
  setPoseBlock(fix.covariance, covariance);
  covariance.block<3, 3>(kVelocity, kVelocity)
      .diagonal()
      .setConstant(velocity.sigma_mps * velocity.sigma_mps);
  covariance.block<3, 3>(kGyroBias, kGyroBias)
      .diagonal()
      .setConstant(gyro_bias_sigma * gyro_bias_sigma);
  covariance.block<3, 3>(kAccelBias, kAccelBias)
      .diagonal()
      .setConstant(config_.accel_turn_on_bias_sigma_mps2 * config_.accel_turn_on_bias_sigma_mps2);
  startAt(state, covariance, *imu, StartPosition::kFromVision, fix.unproven_covariance);
  return MeasurementOutcome::kAccepted;
}

std::vector<InertialNavigator::GatedFix> InertialNavigator::gatedVisionRun() const {
  std::vector<GatedFix> run;
  for (auto it = measurements_.rbegin(); it != measurements_.rend(); ++it) {
    const auto* vision = std::get_if<VisionPayload>(&it->second.payload);
    if (vision == nullptr || !it->second.outcome) {
      continue;
    }
    if (*it->second.outcome != MeasurementOutcome::kGated || !it->second.vision_residual) {
      return {};
    }
    run.push_back({it->first, vision, *it->second.vision_residual});
    if (run.front().stamp_ns - it->first >= config_.vision_gated_restart_after_ns) {
      return run;
    }
  }
  return {};
}

// Position residuals r_i = a + b (t_i - t_mean) + e_i (least squares), attitude
// residuals theta_i = theta_mean + e_i; every e_i within the gate of its fix's
// covariance.
std::optional<InertialNavigator::ResidualDrift> InertialNavigator::commonResidualDrift(
    const std::vector<GatedFix>& run) const {
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
    if (position_error.dot(position_covariance.ldlt().solve(position_error)) >
            gate_by_dimension_[3] ||
        attitude_error.dot(attitude_covariance.ldlt().solve(attitude_error)) >
            gate_by_dimension_[3]) {
      return std::nullopt;
    }
    position_variance = std::max(position_variance, position_covariance.diagonal().maxCoeff());
  }
  drift.velocity_variance = position_variance / time_spread_s2;
  return drift;
}

void InertialNavigator::restartIfVisionKeepsBeingGated() {
  if (snapshots_.empty() || config_.vision_gated_restart_after_ns <= 0) {
    return;
  }
  const std::vector<GatedFix> run = gatedVisionRun();
  if (run.size() < kMinGatedFixesForRestart) {
    return;
  }
  const std::optional<ResidualDrift> drift = commonResidualDrift(run);
  if (!drift) {
    return;
  }
  const GatedFix& newest = run.front();
  const auto after = std::upper_bound(
      snapshots_.begin(), snapshots_.end(), newest.stamp_ns,
      [](int64_t stamp, const Snapshot& snapshot) { return stamp < snapshot.state.stamp_ns; });
  const Snapshot& filter = after == snapshots_.begin() ? snapshots_.front() : *std::prev(after);
  // The filter's velocity, corrected by the drift; its error also grows with
  // the attitude error the fixes show, g |theta| over half the run.
  const double run_s = static_cast<double>(newest.stamp_ns - run.back().stamp_ns) * kNsToS;
  const double tilt_velocity_sigma_mps =
      config_.gravity_mps2 * drift->attitude_offset_rad.norm() * 0.5 * run_s;
  const double velocity_variance =
      filter.covariance.block<3, 3>(kVelocity, kVelocity).diagonal().maxCoeff() +
      drift->velocity_variance + tilt_velocity_sigma_mps * tilt_velocity_sigma_mps;
  const StartVelocity velocity{filter.state.v_world_body + drift->velocity_mps,
                               std::sqrt(velocity_variance)};
  if (startFromVision(bodyFixOf(newest.stamp_ns, *newest.vision), velocity) ==
      MeasurementOutcome::kAccepted) {
    ++counters_.restarts;
  }
}

void InertialNavigator::trackGatedCompass(int64_t stamp_ns, const Measurement& measurement) {
  if (measurement.outcome != MeasurementOutcome::kAccepted &&
      measurement.outcome != MeasurementOutcome::kGated) {
    return;
  }
  const bool compass = std::holds_alternative<YawPayload>(measurement.payload);
  if (measurement.outcome == MeasurementOutcome::kGated && compass &&
      measurement.yaw_residual_rad) {
    gated_compass_.push_back({stamp_ns, *measurement.yaw_residual_rad});
    return;
  }
  if (measurement.outcome == MeasurementOutcome::kAccepted &&
      (compass || std::holds_alternative<VisionPayload>(measurement.payload))) {
    gated_compass_.clear();
  }
}

void InertialNavigator::restartHeadingIfCompassKeepsBeingGated() {
  if (snapshots_.empty() || config_.compass_gated_restart_after_ns <= 0 || gated_compass_.empty() ||
      gated_compass_.back().stamp_ns - gated_compass_.front().stamp_ns <
          config_.compass_gated_restart_after_ns) {
    return;
  }
  std::vector<double> residuals_rad;
  for (const GatedYaw& gated : gated_compass_) {
    residuals_rad.push_back(gated.residual_rad);
  }
  const RobustHeading offset =
      robustCircularMean(residuals_rad, kStartupHeadingGateSigmas * config_.compass_sigma_rad);
  if (offset.inliers < kMinAgreeingCompassFraction * static_cast<double>(residuals_rad.size())) {
    // A compass that wanders: the run slides on.
    gated_compass_.erase(gated_compass_.begin());
    return;
  }
  const Snapshot latest = snapshots_.back();
  NavigationState state = latest.state;
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(offset.heading_rad, Eigen::Vector3d::UnitZ()));
  state.q_world_body = turn * state.q_world_body;
  state.v_world_body = turn * state.v_world_body;
  ErrorCovariance covariance = latest.covariance;
  covariance.row(kAttitude + 2).setZero();
  covariance.col(kAttitude + 2).setZero();
  covariance(kAttitude + 2, kAttitude + 2) = compassYawSigma_rad() * compassYawSigma_rad();
  startAt(state, covariance, latest.imu,
          latest.position_known ? StartPosition::kFromSensors : StartPosition::kUnknown,
          latest.unproven_covariance, latest.velocity_known);
  ++counters_.heading_restarts;
}

PosePrediction InertialNavigator::predictAt(int64_t stamp_ns) const {
  PosePrediction prediction;
  if (snapshots_.empty()) {
    return prediction;
  }
  if (stamp_ns < snapshots_.front().state.stamp_ns) {
    prediction.status = PredictionStatus::kBeforeHistory;
    return prediction;
  }
  const auto after = std::upper_bound(
      snapshots_.begin(), snapshots_.end(), stamp_ns,
      [](int64_t stamp, const Snapshot& snapshot) { return stamp < snapshot.state.stamp_ns; });
  const Snapshot& from = *std::prev(after);
  if (!from.position_known) {
    return prediction;
  }
  Snapshot predicted = from;
  // Between two snapshots the next sample is known; past the last, hold its rates.
  ImuSample target =
      after != snapshots_.end() ? interpolateImu(from.imu, after->imu, stamp_ns) : from.imu;
  target.stamp_ns = stamp_ns;
  if (stamp_ns > predicted.state.stamp_ns) {
    propagate(from.imu, target, predicted);
  }
  prediction.status = PredictionStatus::kOk;
  prediction.T_world_camera =
      cameraPoseOf(predicted.state, predicted.covariance, config_.T_body_camera);
  return prediction;
}

std::optional<NavigatorEstimate> InertialNavigator::state() const {
  if (snapshots_.empty() || !snapshots_.back().position_known) {
    return std::nullopt;
  }
  const Snapshot& latest = snapshots_.back();
  return NavigatorEstimate{latest.state,
                           reportedCovariance(latest.covariance, latest.unproven_covariance,
                                              latest.fix_offset_covariance)};
}

PoseWithCovariance InertialNavigator::cameraPose(const NavigatorEstimate& estimate) const {
  return cameraPoseOf(estimate.state, estimate.covariance, config_.T_body_camera);
}

NavigatorHealth InertialNavigator::health() const {
  NavigatorHealth health = counters_;
  if (snapshots_.empty()) {
    health.mode = NavigatorMode::kInitialising;
    return health;
  }
  const Snapshot& latest = snapshots_.back();
  health.stamp_ns = latest.state.stamp_ns;
  health.zero_velocity_updates = latest.zero_velocity_updates;
  if (!latest.position_known) {
    health.mode = NavigatorMode::kInitialising;
    return health;
  }
  if (latest.at_last_vision) {
    health.since_vision_fix_ns = latest.state.stamp_ns - latest.at_last_vision->stamp_ns;
  }
  const ErrorCovariance covariance = reportedCovariance(
      latest.covariance, latest.unproven_covariance, latest.fix_offset_covariance);
  health.position_sigma_m = std::sqrt(covariance.block<3, 3>(kPosition, kPosition)
                                          .selfadjointView<Eigen::Lower>()
                                          .eigenvalues()
                                          .maxCoeff());
  health.yaw_sigma_rad = std::sqrt(covariance(kAttitude + 2, kAttitude + 2));
  if (health.position_sigma_m > config_.lost_position_sigma_m) {
    health.mode = NavigatorMode::kLost;
  } else if (health.since_vision_fix_ns &&
             *health.since_vision_fix_ns <= config_.tracking_timeout_ns) {
    health.mode = NavigatorMode::kTracking;
  } else {
    health.mode = NavigatorMode::kDeadReckoning;
  }
  return health;
}

}  // namespace lineloc
