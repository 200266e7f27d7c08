#include "robot/inertial/startup_alignment.h"

#include <algorithm>
#include <cmath>
#include <utility>

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
// Position sigma of a start without DGPS: unknown. A DGPS fix up to tens of
// kilometres from the site's origin passes the gate; in double precision a
// 1e8 m^2 variance rounds by 1e-8 m^2, a ten-thousandth of a vision fix's.
constexpr double kUnknownPositionSigma_m = 1e4;
// Compass readings needed for a start-up heading (1 s at 10 Hz).
constexpr size_t kMinStartupCompassReadings = 10;
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

Eigen::Quaterniond quaternionFromYawPitchRoll(double yaw, double pitch, double roll) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
}

}  // namespace

BodyFix bodyFixOf(int64_t stamp_ns, const VisionPayload& vision,
                  const Eigen::Isometry3d& T_body_camera) {
  const Eigen::Isometry3d& T_world_camera = vision.T_world_camera.pose;
  return {stamp_ns, T_world_camera * T_body_camera.inverse(),
          bodyPoseCovarianceOf(T_world_camera,
                               vision.T_world_camera.covariance - vision.unproven_covariance,
                               T_body_camera),
          bodyPoseCovarianceOf(T_world_camera, vision.unproven_covariance, T_body_camera)};
}

StartupAlignment::StartupAlignment(const InertialNavigatorConfig& config)
    : config_(config),
      compass_yaw_sigma_rad_(compassYawSigma_rad(config)),
      alignment_detector_(config.alignment) {}

void StartupAlignment::addImu(const ImuSample& sample) {
  alignment_detector_.add(sample);
  moved_since_power_on_ = moved_since_power_on_ || alignment_detector_.isMoving();
  if (auto alignment = alignment_detector_.alignment()) {
    alignment_ = alignment;
  }
}

void StartupAlignment::addGps(const GpsFix& fix) {
  gps_ = fix;
}

bool StartupAlignment::addGpsVelocity(const GpsVelocity& velocity) {
  // A robot cruising on a smooth road can look as still to the IMU as a
  // standing one; a speed the receiver measures beyond its noise on two
  // consecutive epochs is motion, one the next epoch denies multipath.
  const bool claimed = motionClaimed();
  const bool moving = isMotion(velocity);
  moved_since_power_on_ = moved_since_power_on_ || (moving && claimed);
  velocities_.push_back(velocity);
  if (velocities_.size() > 2) {
    velocities_.pop_front();
  }
  return !moving && claimed;
}

void StartupAlignment::addCompassYaw(const TimedYaw& yaw) {
  compass_yaws_.push_back(yaw);
}

std::optional<StartVelocity> StartupAlignment::addVisionFix(const BodyFix& fix) {
  const std::optional<BodyFix> previous = std::exchange(vision_, fix);
  if (!mayHaveMoved() && alignment_detector_.isStill()) {
    return StartVelocity{Eigen::Vector3d::Zero(), kStillVelocitySigma_mps};
  }
  const int64_t baseline_ns = previous ? fix.stamp_ns - previous->stamp_ns : 0;
  if (baseline_ns <= 0 || baseline_ns > kMaxVelocityBaseline_ns) {
    return std::nullopt;
  }
  const double dt = static_cast<double>(baseline_ns) * kNsToS;
  const double position_variance = fix.covariance.topLeftCorner<3, 3>().diagonal().maxCoeff() +
                                   previous->covariance.topLeftCorner<3, 3>().diagonal().maxCoeff();
  return StartVelocity{(fix.T_world_body.translation() - previous->T_world_body.translation()) / dt,
                       std::sqrt(position_variance) / dt + 0.5 * kMaxGroundAcceleration_mps2 * dt};
}

void StartupAlignment::prune(int64_t stamp_ns) {
  const int64_t compass_from_ns = stamp_ns - config_.alignment.window_ns;
  while (!compass_yaws_.empty() && compass_yaws_.front().stamp_ns < compass_from_ns) {
    compass_yaws_.pop_front();
  }
}

void StartupAlignment::clear() {
  gps_.reset();
  velocities_.clear();
  compass_yaws_.clear();
  vision_.reset();
}

bool StartupAlignment::isMotion(const GpsVelocity& velocity) const {
  return velocity.v_world_mps.norm() > kMovingSpeedSigmas * config_.gps_velocity_sigma_mps;
}

bool StartupAlignment::motionClaimed() const {
  return !velocities_.empty() && isMotion(velocities_.back());
}

bool StartupAlignment::mayHaveMoved() const {
  return moved_since_power_on_ || motionClaimed();
}

Eigen::Vector3d StartupAlignment::placeAtDgps(const GpsFix* fix, NavigationState& state) const {
  if (fix == nullptr) {
    return Eigen::Vector3d::Constant(kUnknownPositionSigma_m);
  }
  state.p_world_body = fix->p_world_antenna - state.q_world_body * config_.p_body_gps_antenna;
  return gpsFixSigmas(*fix, config_);
}

Eigen::Vector3d StartupAlignment::initialGyroBias(bool stood_still, double& sigma_radps) const {
  if (!alignment_ || !stood_still) {
    sigma_radps = config_.gyro_turn_on_bias_sigma_radps;
    return Eigen::Vector3d::Zero();
  }
  // Mean of white rate noise over T seconds: sigma^2 = N^2 / T.
  sigma_radps = config_.imu_noise.gyro_noise_radps_per_sqrt_hz / std::sqrt(alignment_->duration_s);
  return alignment_->gyro_bias_radps;
}

std::optional<NavigatorStart> StartupAlignment::standing(const MeasurementHistory& history) const {
  // Only while standing still since power-on: the start covariance assumes it,
  // and a robot cruising on a smooth road can be as quiet as a standing one.
  const auto alignment = alignment_detector_.alignment();
  const std::optional<ImuSample> latest = history.latestImu();
  if (mayHaveMoved() || !alignment || !latest ||
      (!start_pose_ && compass_yaws_.size() < kMinStartupCompassReadings)) {
    return std::nullopt;
  }
  double yaw_rad = 0.0;
  double yaw_sigma_rad = compass_yaw_sigma_rad_;
  if (start_pose_) {
    yaw_rad = yawOf(Eigen::Quaterniond(start_pose_->T_world_body.linear()));
    // The pose covariance is of [dp; dtheta]: dtheta_z, the world yaw, is its sixth.
    yaw_sigma_rad = std::sqrt(start_pose_->covariance(5, 5));
  } else {
    std::vector<double> compass_yaws_rad;
    for (const TimedYaw& yaw : compass_yaws_) {
      compass_yaws_rad.push_back(yaw.yaw_rad);
    }
    yaw_rad = robustCircularMean(compass_yaws_rad, kCompassGateSigmas * config_.compass_sigma_rad)
                  .heading_rad;
  }
  NavigatorStart start;
  NavigationState& state = start.state;
  state.stamp_ns = latest->stamp_ns;
  state.q_world_body =
      quaternionFromYawPitchRoll(yaw_rad, alignment->pitch_rad, alignment->roll_rad);
  // Without a position only the IMU says the robot stands (see the header):
  // the velocity is unknown, and the window's mean rate may be the body
  // pitching.
  const bool position_known = start_pose_ || gps_;
  Eigen::Matrix3d position_covariance;
  if (start_pose_) {
    state.p_world_body = start_pose_->T_world_body.translation();
    position_covariance = start_pose_->covariance.topLeftCorner<3, 3>();
  } else {
    position_covariance =
        placeAtDgps(gps_ ? &*gps_ : nullptr, state).cwiseAbs2().asDiagonal().toDenseMatrix();
  }
  double gyro_bias_sigma = 0.0;
  state.gyro_bias_radps = initialGyroBias(position_known, gyro_bias_sigma);
  // A tilt error of b_a / g hides behind an accelerometer bias b_a.
  const double tilt_sigma = config_.accel_turn_on_bias_sigma_mps2 / config_.gravity_mps2;
  const double velocity_sigma_mps =
      position_known ? kStillVelocitySigma_mps : config_.max_ground_speed_mps;
  ErrorVector sigma;
  sigma << Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(velocity_sigma_mps), tilt_sigma,
      tilt_sigma, yaw_sigma_rad, Eigen::Vector3d::Constant(gyro_bias_sigma),
      Eigen::Vector3d::Constant(config_.accel_turn_on_bias_sigma_mps2);
  start.covariance = sigma.cwiseAbs2().asDiagonal();
  start.covariance.block<3, 3>(kPosition, kPosition) = position_covariance;
  start.imu = *latest;
  start.position = position_known ? StartPosition::kFromSensors : StartPosition::kUnknown;
  start.velocity_known = position_known;
  return start;
}

void StartupAlignment::setStartPose(const BodyFix& pose) {
  start_pose_ = pose;
}

std::optional<NavigatorStart> StartupAlignment::inMotion(const MeasurementHistory& history) {
  // Only once the robot has moved since power-on: standing, the start above
  // levels better. Tried once per pair of velocities, when the IMU has passed
  // the second (and the DGPS fix of its epoch has come).
  const std::optional<ImuSample> latest = history.latestImu();
  if (!moved_since_power_on_ || velocities_.size() < 2 || !latest ||
      latest->stamp_ns <= velocities_.back().stamp_ns) {
    return std::nullopt;
  }
  const GpsVelocity from = velocities_.front();
  const GpsVelocity to = velocities_.back();
  velocities_.pop_front();
  if (to.stamp_ns - from.stamp_ns > kMaxVelocityMatchingBaseline_ns) {
    return std::nullopt;
  }
  const std::optional<std::vector<ImuSample>> imu = history.imuOver(from.stamp_ns, to.stamp_ns);
  if (!imu) {
    return std::nullopt;
  }
  const InMotionAlignmentNoise noise{
      config_.gravity_mps2, config_.gps_velocity_sigma_mps, config_.accel_turn_on_bias_sigma_mps2,
      config_.gyro_turn_on_bias_sigma_radps, kCompassGateSigmas * config_.compass_sigma_rad};
  const std::vector<TimedYaw> compass_yaws(compass_yaws_.begin(), compass_yaws_.end());
  const std::optional<InMotionAttitude> attitude = alignInMotion(
      *imu, from.stamp_ns, from.v_world_mps, to.stamp_ns, to.v_world_mps, compass_yaws, noise);
  if (!attitude) {
    return std::nullopt;
  }
  NavigatorStart start;
  start.imu = imu->back();
  NavigationState& state = start.state;
  state.stamp_ns = to.stamp_ns;
  state.q_world_body = attitude->q_world_body;
  // v_body = v_antenna - R (omega x r).
  state.v_world_body = Eigen::Vector3d(to.v_world_mps.x(), to.v_world_mps.y(), 0.0) -
                       state.q_world_body * start.imu.gyro_radps.cross(config_.p_body_gps_antenna);
  const bool position_known = gps_ && std::abs(gps_->stamp_ns - to.stamp_ns) <= kSameEpoch_ns;
  const Eigen::Vector3d position_sigma_m = placeAtDgps(position_known ? &*gps_ : nullptr, state);
  double gyro_bias_sigma = 0.0;
  state.gyro_bias_radps = initialGyroBias(false, gyro_bias_sigma);
  const double vertical_velocity_sigma =
      std::max(kStillVelocitySigma_mps, kSteepGrade * to.v_world_mps.norm());
  ErrorVector sigma;
  sigma << position_sigma_m, config_.gps_velocity_sigma_mps, config_.gps_velocity_sigma_mps,
      vertical_velocity_sigma, attitude->tilt_sigma_rad, attitude->tilt_sigma_rad,
      compass_yaw_sigma_rad_, Eigen::Vector3d::Constant(gyro_bias_sigma),
      Eigen::Vector3d::Constant(config_.accel_turn_on_bias_sigma_mps2);
  start.covariance = sigma.cwiseAbs2().asDiagonal();
  start.position = position_known ? StartPosition::kFromSensors : StartPosition::kUnknown;
  return start;
}

std::optional<NavigatorStart> StartupAlignment::fromVision(
    const BodyFix& fix, const StartVelocity& velocity, const MeasurementHistory& history) const {
  const std::optional<ImuSample> imu = history.imuAt(fix.stamp_ns);
  if (!imu) {
    return std::nullopt;
  }
  NavigatorStart start;
  start.imu = *imu;
  start.position = StartPosition::kFromVision;
  start.unproven_covariance = fix.unproven_covariance;
  NavigationState& state = start.state;
  state.stamp_ns = fix.stamp_ns;
  state.p_world_body = fix.T_world_body.translation();
  state.q_world_body = Eigen::Quaterniond(fix.T_world_body.linear()).normalized();
  state.v_world_body = velocity.v_world_mps;
  double gyro_bias_sigma = 0.0;
  state.gyro_bias_radps = initialGyroBias(!mayHaveMoved(), gyro_bias_sigma);
  ErrorCovariance& covariance = start.covariance;
  covariance.setZero();
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
  return start;
}

}  // namespace lineloc
