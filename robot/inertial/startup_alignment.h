// The start of the navigation filter (inertial_navigator.h) from what the
// sensors tell before it, and what each start knows (NavigatorStart).
//
// Standing. Standing still for `alignment.window_ns` gives roll, pitch and
// gyro bias (stillness_detector.h); the compass, corrected for magnetic
// declination and meridian convergence, gives yaw, the robust mean of the
// window's readings (robust_heading.h: a disturbance over part of the window
// is left out), with one reading's sigma_c (compassYawSigma_rad); DGPS gives
// position; all with large covariances; only if the robot has not moved since
// power-on. A start pose, where the robot is known to stand (an operator's or
// a dock's, for a robot without GNSS), gives position and yaw instead, with
// its covariance. Without a DGPS fix by the end of that window the filter starts
// all the same, its position unknown (kUnknownPositionSigma_m), and the first
// DGPS or vision fix accepted gives it. Such a start, which only the IMU
// calls still, may be a cruise as quiet as a standstill: it takes the
// velocity as unknown (sigma max_ground_speed_mps) and the gyro bias within
// its turn-on spread, and holds zero-velocity updates off until a DGPS
// velocity or a vision fix is accepted.
//
// Moving. A robot that has moved since power-on (started while driving, or
// whose software restarted mid-drive) starts from two consecutive DGPS
// velocities (the receiver's Doppler, NMEA RMC) at most
// kMaxVelocityMatchingBaseline_ns apart: roll and pitch by velocity matching
// against the IMU between them, yaw from the compass readings between them
// (in_motion_alignment.h); velocity the receiver's, v_body = v_antenna -
// R (omega x r), the vertical one zero within a steep street's grade times the
// speed; position the DGPS fix of the same epoch, or unknown as above; gyro
// and accelerometer biases zero within their turn-on spread.
//
// DGPS velocities. Two consecutive ones beyond kMovingSpeedSigmas of their
// noise say the robot moves and bar the standstill start; one alone may be
// multipath (a signal reflected off a façade throws the Doppler by a metre
// per second): it holds the standstill start until the next epoch confirms or
// denies it, and a denied one is counted gated.
//
// From vision. Vision fixes before any start (the window not yet full, or a
// robot that never stood still and has no DGPS velocity) start the filter
// from their pose: at once when it has stood still since power-on, else from
// two fixes at most kMaxVelocityBaseline_ns apart, whose difference gives the
// velocity, v = dp / dt with sigma from both positions plus the speed change
// a dt / 2 the mean velocity misses at a ground robot's acceleration a. The
// restart from vision (restart_monitor.h) starts the same way.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "robot/inertial/imu_sample.h"
#include "robot/inertial/in_motion_alignment.h"
#include "robot/inertial/inertial_navigator_config.h"
#include "robot/inertial/measurement_history.h"
#include "robot/inertial/navigation_state.h"
#include "robot/inertial/navigator_measurements.h"
#include "robot/inertial/stillness_detector.h"

namespace lineloc {

// Compass readings farther than this many compass sigmas from their circular
// median are disturbed and left out of a heading (robust_heading.h).
inline constexpr double kCompassGateSigmas = 3.0;

// What a start knows of the position: nothing yet, a sensor's, or a vision
// fix's, which counts as applied.
enum class StartPosition { kUnknown, kFromSensors, kFromVision };

// A start of the filter: its state and covariance at the IMU reading `imu`.
struct NavigatorStart {
  NavigationState state;
  ErrorCovariance covariance = ErrorCovariance::Identity();
  ImuSample imu;
  StartPosition position = StartPosition::kFromSensors;
  // The unproven part of a start's pose covariance, as of a vision fix's
  // (body pose error [dp; dtheta], correlated_fix_model.h).
  Matrix6d unproven_covariance = Matrix6d::Zero();
  // False for a start whose stillness only the IMU saw.
  bool velocity_known = true;
};

// A vision fix as the body's pose, the covariance of what tracking measured
// (R - U) and the unproven part U.
struct BodyFix {
  int64_t stamp_ns = 0;
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
  Matrix6d covariance = Matrix6d::Identity();
  Matrix6d unproven_covariance = Matrix6d::Zero();
};

BodyFix bodyFixOf(int64_t stamp_ns, const VisionPayload& vision,
                  const Eigen::Isometry3d& T_body_camera);

// The velocity a start from a vision fix takes, the same sigma on each axis.
struct StartVelocity {
  Eigen::Vector3d v_world_mps = Eigen::Vector3d::Zero();
  double sigma_mps = 0.0;
};

class StartupAlignment {
 public:
  explicit StartupAlignment(const InertialNavigatorConfig& config);

  // The readings before a start.
  void addImu(const ImuSample& sample);
  void addGps(const GpsFix& fix);
  // Returns true when `velocity` denies the motion the one before it claimed.
  bool addGpsVelocity(const GpsVelocity& velocity);
  void addCompassYaw(const TimedYaw& yaw);
  // The body's pose where the robot stands from power-on (see above).
  void setStartPose(const BodyFix& pose);
  // Remembers `fix` and returns the velocity a start from it takes: zero
  // when the robot has stood still since power-on, else from the fix before
  // it (nullopt: none within kMaxVelocityBaseline_ns).
  std::optional<StartVelocity> addVisionFix(const BodyFix& fix);
  // Drops the compass yaws older than the still window before `stamp_ns`.
  void prune(int64_t stamp_ns);
  // Forgets the readings once the filter has started; whether the robot
  // moved since power-on, and its last still window, stay.
  void clear();

  // The standing start, when the robot has stood still since power-on for
  // the window, with the compass readings it needs; `history` holds the IMU.
  std::optional<NavigatorStart> standing(const MeasurementHistory& history) const;
  // The start in motion, once the robot has moved since power-on and the IMU
  // has passed the second of two DGPS velocities; tried once per pair.
  std::optional<NavigatorStart> inMotion(const MeasurementHistory& history);
  // The start at `fix`'s pose and covariance with `velocity`, the IMU biases
  // from standing still or their turn-on spread; nullopt when `history`
  // holds no IMU reading at the fix's time.
  std::optional<NavigatorStart> fromVision(const BodyFix& fix, const StartVelocity& velocity,
                                           const MeasurementHistory& history) const;

 private:
  // A speed beyond kMovingSpeedSigmas of the DGPS velocity's noise.
  bool isMotion(const GpsVelocity& velocity) const;
  // The newest DGPS velocity claims motion no later epoch has confirmed or denied yet.
  bool motionClaimed() const;
  // Moved since power-on, or a DGPS velocity says so unconfirmed.
  bool mayHaveMoved() const;
  // A start's position: `fix`'s antenna moved to the body at the state's
  // attitude, with DGPS's sigma; without a fix, unknown
  // (kUnknownPositionSigma_m). Returns the sigma per axis.
  Eigen::Vector3d placeAtDgps(const GpsFix* fix, NavigationState& state) const;
  // The gyro bias of the last still window when `stood_still` says the robot
  // stood there, else zero within its turn-on spread: a window only the IMU
  // calls still may be a cruise on a changing grade, whose mean rate is the
  // body pitching, not the bias.
  Eigen::Vector3d initialGyroBias(bool stood_still, double& sigma_radps) const;

  InertialNavigatorConfig config_;
  double compass_yaw_sigma_rad_;
  StillnessDetector alignment_detector_;
  std::optional<StaticAlignment> alignment_;
  bool moved_since_power_on_ = false;
  std::optional<GpsFix> gps_;
  // The last two DGPS velocities, oldest first.
  std::deque<GpsVelocity> velocities_;
  std::deque<TimedYaw> compass_yaws_;
  std::optional<BodyFix> vision_;
  std::optional<BodyFix> start_pose_;
};

}  // namespace lineloc
