#include "robot/inertial/inertial_navigator.h"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "robot/inertial/correlated_fix_model.h"
#include "robot/inertial/measurement_models.h"

namespace lineloc {
namespace {

const InertialNavigatorConfig& validated(const InertialNavigatorConfig& config) {
  validate(config);
  return config;
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

// The counts of the outcomes decided before the history and in it.
MeasurementCounters sum(const MeasurementCounters& a, const MeasurementCounters& b) {
  return {a.accepted + b.accepted, a.gated + b.gated,       a.degenerate + b.degenerate,
          a.skipped + b.skipped,   a.too_late + b.too_late, a.invalid + b.invalid};
}

}  // namespace

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
    : config_(validated(config)),
      filter_(config),
      zero_velocity_detector_(config.zero_velocity),
      history_(config.history_ns),
      startup_(config),
      vision_restart_(config),
      compass_restart_(config) {}

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
  const bool started = history_.started();
  history_.addImu({sample, zero_velocity_detector_.isStill()}, filter_);
  if (started) {
    restartIfVisionKeepsBeingGated();
  } else {
    startup_.addImu(sample);
    if (!startIfAny(startup_.standing(history_))) {
      startInMotion();
    }
  }
  prune();
  restartHeadingIfCompassKeepsBeingGated();
}

void InertialNavigator::addGps(const GpsFix& fix) {
  if (!fix.p_world_antenna.allFinite()) {
    ++counters_.gps.invalid;
    return;
  }
  if (!history_.started()) {
    startup_.addGps(fix);
    startIfAny(startup_.standing(history_));
    return;
  }
  const Eigen::Vector3d sigmas = gpsFixSigmas(fix, config_);
  history_.add(fix.stamp_ns,
               Measurement(GpsPayload{fix.p_world_antenna, sigmas.cwiseAbs2().asDiagonal()}),
               filter_);
}

void InertialNavigator::addGpsVelocity(const GpsVelocity& velocity) {
  if (!velocity.v_world_mps.allFinite()) {
    ++counters_.gps_velocity.invalid;
    return;
  }
  if (history_.started()) {
    history_.add(velocity.stamp_ns, Measurement(GpsVelocityPayload{velocity.v_world_mps}), filter_);
    return;
  }
  if (startup_.addGpsVelocity(velocity)) {
    ++counters_.gps_velocity.gated;
  }
  startInMotion();
}

void InertialNavigator::startInMotion() {
  if (startIfAny(startup_.inMotion(history_))) {
    // The start took both velocities.
    counters_.gps_velocity.accepted += 2;
  }
}

void InertialNavigator::addCompass(const CompassReading& reading) {
  if (!std::isfinite(reading.magnetic_heading_rad)) {
    ++counters_.compass.invalid;
    return;
  }
  const double yaw_rad = yawFromCompass(reading.magnetic_heading_rad);
  if (!history_.started()) {
    startup_.addCompassYaw({reading.stamp_ns, yaw_rad});
    startIfAny(startup_.standing(history_));
    return;
  }
  history_.add(reading.stamp_ns, Measurement(YawPayload{yaw_rad}), filter_);
}

double InertialNavigator::yawFromCompass(double magnetic_heading_rad) const {
  return wrapAngle(M_PI_2 - (magnetic_heading_rad + config_.magnetic_declination_rad +
                             config_.grid_bearing_of_true_north_rad));
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
  if (!history_.started()) {
    const BodyFix fix = bodyFixOf(stamp_ns, vision, config_.T_body_camera);
    const std::optional<StartVelocity> velocity = startup_.addVisionFix(fix);
    const MeasurementOutcome outcome =
        velocity ? startFromVision(fix, *velocity) : MeasurementOutcome::kSkipped;
    ++counterOf(counters_.vision, outcome);
    return outcome;
  }
  const MeasurementOutcome outcome = history_.add(stamp_ns, Measurement(vision), filter_);
  restartIfVisionKeepsBeingGated();
  return outcome;
}

bool InertialNavigator::initialise(const NavigationState& state,
                                   const ErrorCovariance& covariance) {
  const std::optional<ImuSample> imu = history_.imuAt(state.stamp_ns);
  if (!imu) {
    return false;
  }
  startAt({state, covariance, *imu, StartPosition::kFromSensors});
  return true;
}

void InertialNavigator::setStartPose(const PoseWithCovariance& T_world_camera) {
  startup_.setStartPose(bodyFixOf(0, VisionPayload{T_world_camera}, config_.T_body_camera));
}

void InertialNavigator::startAt(const NavigatorStart& start) {
  FilterSnapshot snapshot;
  snapshot.state = start.state;
  snapshot.covariance = start.covariance;
  snapshot.imu = start.imu;
  snapshot.last_zero_velocity_ns = start.state.stamp_ns;
  snapshot.position_known = start.position != StartPosition::kUnknown;
  snapshot.velocity_known = start.velocity_known;
  snapshot.fixes.unproven_covariance = start.unproven_covariance;
  if (start.position == StartPosition::kFromVision) {
    snapshot.fixes.at_last_fix = start.state;
  }
  startup_.clear();
  compass_restart_.clear();
  history_.start(snapshot, filter_);
}

bool InertialNavigator::startIfAny(const std::optional<NavigatorStart>& start) {
  if (start) {
    startAt(*start);
  }
  return start.has_value();
}

MeasurementOutcome InertialNavigator::startFromVision(const BodyFix& fix,
                                                      const StartVelocity& velocity) {
  return startIfAny(startup_.fromVision(fix, velocity, history_)) ? MeasurementOutcome::kAccepted
                                                                  : MeasurementOutcome::kTooLate;
}

void InertialNavigator::restartIfVisionKeepsBeingGated() {
  const std::optional<VisionRestart> restart = vision_restart_.restart(history_);
  if (restart &&
      startFromVision(restart->fix, restart->velocity) == MeasurementOutcome::kAccepted) {
    ++counters_.restarts;
  }
}

void InertialNavigator::prune() {
  for (const auto& [stamp_ns, measurement] : history_.prune()) {
    compass_restart_.add(stamp_ns, measurement);
  }
  // Start-up heading: the compass readings of the last still window.
  startup_.prune(history_.latestImu()->stamp_ns);
}

void InertialNavigator::restartHeadingIfCompassKeepsBeingGated() {
  if (history_.started() && startIfAny(compass_restart_.restart(history_.latest()))) {
    ++counters_.heading_restarts;
  }
}

PosePrediction InertialNavigator::predictAt(int64_t stamp_ns) const {
  PosePrediction prediction;
  if (!history_.started()) {
    return prediction;
  }
  if (stamp_ns < history_.oldest().state.stamp_ns) {
    prediction.status = PredictionStatus::kBeforeHistory;
    return prediction;
  }
  if (!history_.at(stamp_ns).position_known) {
    return prediction;
  }
  const FilterSnapshot predicted = history_.predict(stamp_ns, filter_);
  prediction.status = PredictionStatus::kOk;
  prediction.T_world_camera =
      cameraPoseOf(predicted.state, predicted.covariance, config_.T_body_camera);
  return prediction;
}

std::optional<NavigatorEstimate> InertialNavigator::state() const {
  if (!history_.started() || !history_.latest().position_known) {
    return std::nullopt;
  }
  const FilterSnapshot& latest = history_.latest();
  const std::optional<ImuSample> sample = history_.latestImu();
  return NavigatorEstimate{latest.state, filter_.reportedCovariance(latest),
                           sample
                               ? Eigen::Vector3d(sample->gyro_radps - latest.state.gyro_bias_radps)
                               : Eigen::Vector3d::Zero()};
}

PoseWithCovariance InertialNavigator::cameraPose(const NavigatorEstimate& estimate) const {
  return cameraPoseOf(estimate.state, estimate.covariance, config_.T_body_camera);
}

NavigatorHealth InertialNavigator::health() const {
  NavigatorHealth health = counters_;
  health.vision = sum(counters_.vision, history_.counters(MeasurementKind::kVision));
  health.gps = sum(counters_.gps, history_.counters(MeasurementKind::kGps));
  health.gps_velocity =
      sum(counters_.gps_velocity, history_.counters(MeasurementKind::kGpsVelocity));
  health.compass = sum(counters_.compass, history_.counters(MeasurementKind::kCompass));
  if (!history_.started()) {
    health.mode = NavigatorMode::kInitialising;
    return health;
  }
  const FilterSnapshot& latest = history_.latest();
  health.stamp_ns = latest.state.stamp_ns;
  health.zero_velocity_updates = latest.zero_velocity_updates;
  if (!latest.position_known) {
    health.mode = NavigatorMode::kInitialising;
    return health;
  }
  if (latest.fixes.at_last_fix) {
    health.since_vision_fix_ns = latest.state.stamp_ns - latest.fixes.at_last_fix->stamp_ns;
  }
  const ErrorCovariance covariance = filter_.reportedCovariance(latest);
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
