// Onboard inertial navigation (paper §1.2): a strapdown IMU carries the pose
// between fixes; the backbone's vision fixes correct its drift; DGPS and the
// compass start it. A 15-state error-state Kalman filter (strapdown.h,
// error_state_update.h) runs at IMU rate.
//
// The navigator checks its inputs and composes the parts of the filter:
//  - startup_alignment.h: before any start, the readings start the filter:
//    standing (stillness, compass, DGPS), in motion (two DGPS velocities) or
//    from vision fixes; each start states what it knows of the position and
//    the velocity.
//  - navigation_filter.h: the filter's step, propagation between two IMU
//    readings and the update with each measurement, gated at
//    `gate_probability`.
//  - measurement_history.h: a snapshot per IMU sample and every measurement
//    over `history_ns`, replayed from a late measurement's time, so that it
//    gives the state an on-time one would.
//  - correlated_fix_model.h: the vision fixes' correlated error (an unchanged
//    view, the share over metres of travel, the unproven offset): the noise a
//    fix updates with and the covariance the filter reports.
//  - restart_monitor.h: vision fixes, or compass readings, gated for long in
//    agreement restart the filter, or its heading.
// The settings are inertial_navigator_config.h's, the measurements' types
// navigator_measurements.h's.
// Before a start the readings go to the start-up; after it, to the history.
// Each IMU sample steps the filter (or tries the starts), then the vision
// restart is checked, the history pruned (the readings leaving it feed the
// compass's monitor) and the heading restart checked; each vision fix checks
// the vision restart too.
//
// A start without DGPS knows no position until a DGPS or vision fix is
// accepted; until then predictAt, state and health say "initialising": a
// prediction with no position would send the backbone's search to the wrong
// street.
//
// Bad input (non-finite or saturated IMU samples, time going backwards,
// duplicate stamps, invalid fixes) is dropped and counted; IMU gaps are
// propagated across and counted.
#pragma once

#include <cstdint>
#include <optional>

#include "common/geometry/pose.h"
#include "robot/inertial/imu_sample.h"
#include "robot/inertial/inertial_navigator_config.h"
#include "robot/inertial/measurement_history.h"
#include "robot/inertial/navigation_filter.h"
#include "robot/inertial/navigation_state.h"
#include "robot/inertial/navigator_measurements.h"
#include "robot/inertial/restart_monitor.h"
#include "robot/inertial/startup_alignment.h"
#include "robot/inertial/stillness_detector.h"

namespace lineloc {

struct ImuCounters {
  int64_t accepted = 0;
  int64_t non_finite = 0;
  int64_t saturated = 0;
  int64_t out_of_order = 0;
  int64_t duplicate = 0;
  int64_t gaps = 0;
};

enum class NavigatorMode { kInitialising, kTracking, kDeadReckoning, kLost };
const char* toString(NavigatorMode mode);

struct NavigatorHealth {
  NavigatorMode mode = NavigatorMode::kInitialising;
  int64_t stamp_ns = 0;
  std::optional<int64_t> since_vision_fix_ns;
  double position_sigma_m = 0.0;  // square root of the largest eigenvalue
  double yaw_sigma_rad = 0.0;
  MeasurementCounters vision;
  MeasurementCounters gps;
  // Accepted: those fused and the two a start in motion took; gated, also
  // those before a start that claimed motion the next epoch denied.
  MeasurementCounters gps_velocity;
  MeasurementCounters compass;
  int64_t zero_velocity_updates = 0;
  int64_t restarts = 0;          // from vision, after vision_gated_restart_after_ns of gated fixes
  int64_t heading_restarts = 0;  // from the compass, after compass_gated_restart_after_ns
  ImuCounters imu;
};

struct NavigatorEstimate {
  NavigationState state;
  ErrorCovariance covariance = ErrorCovariance::Identity();
  // The body's rate of turn in its own frame: the last IMU sample's, less the
  // gyro bias (its covariance is the bias's, covariance's kGyroBias block).
  Eigen::Vector3d omega_body_radps = Eigen::Vector3d::Zero();
};

enum class PredictionStatus { kOk, kNotInitialised, kBeforeHistory };

struct PosePrediction {
  PredictionStatus status = PredictionStatus::kNotInitialised;
  PoseWithCovariance T_world_camera;
};

class InertialNavigator {
 public:
  // Throws std::invalid_argument naming the first invalid setting.
  explicit InertialNavigator(const InertialNavigatorConfig& config);

  // A sample in the IMU frame (rotated here by R_body_imu).
  void addImu(const ImuSample& sample_imu);
  void addGps(const GpsFix& fix);
  void addGpsVelocity(const GpsVelocity& velocity);
  void addCompass(const CompassReading& reading);
  // `unproven_covariance`: the part of T_world_camera.covariance its error
  // shares with the fixes after it (correlated_fix_model.h); within it, else
  // kInvalid.
  MeasurementOutcome applyVisionFix(int64_t stamp_ns, const PoseWithCovariance& T_world_camera,
                                    const Matrix6d& unproven_covariance = Matrix6d::Zero());

  // Starts the filter from a known state at a time the IMU samples given so far
  // cover. Returns false (and does nothing) when they do not.
  bool initialise(const NavigationState& state, const ErrorCovariance& covariance);
  // Where the camera stands from power-on until the filter starts (an
  // operator's or a dock's pose, for a robot without GNSS): the standing start
  // takes its position and yaw instead of DGPS's and the compass's
  // (startup_alignment.h). Call before the first IMU sample.
  void setStartPose(const PoseWithCovariance& T_world_camera);

  // T_world_camera and its covariance at `stamp_ns` (a frame's exposure time),
  // using the configured T_body_camera; beyond the last IMU sample the last
  // rates are held. The covariance leaves the fixes' unproven part out
  // (correlated_fix_model.h). kNotInitialised also where the position was not
  // yet known.
  PosePrediction predictAt(int64_t stamp_ns) const;
  // The state after the last IMU sample, with the covariance the filter
  // reports (the unproven offset and the fixes' shared error in it,
  // correlated_fix_model.h); nullopt before initialisation, or while the
  // position is unknown.
  std::optional<NavigatorEstimate> state() const;
  // The camera's pose and covariance in `estimate` (state()'s), through the
  // configured T_body_camera.
  PoseWithCovariance cameraPose(const NavigatorEstimate& estimate) const;
  NavigatorHealth health() const;

 private:
  bool acceptImu(const ImuSample& sample);
  void startAt(const NavigatorStart& start);
  // Starts at `start`, if any; returns whether it did.
  bool startIfAny(const std::optional<NavigatorStart>& start);
  void startInMotion();
  // kAccepted, or kTooLate when the IMU does not cover the fix's time.
  MeasurementOutcome startFromVision(const BodyFix& fix, const StartVelocity& velocity);
  void restartIfVisionKeepsBeingGated();
  void prune();
  void restartHeadingIfCompassKeepsBeingGated();
  // The body's world yaw: grid bearing = magnetic + declination + grid
  // bearing of true north; yaw = pi/2 - grid bearing, anticlockwise from east.
  double yawFromCompass(double magnetic_heading_rad) const;

  InertialNavigatorConfig config_;
  NavigationFilter filter_;
  StillnessDetector zero_velocity_detector_;
  MeasurementHistory history_;
  StartupAlignment startup_;
  VisionRestartMonitor vision_restart_;
  CompassRestartMonitor compass_restart_;
  // The measurements' outcomes decided outside the history (invalid, before
  // a start), the restarts and the IMU's counters.
  NavigatorHealth counters_;
  std::optional<int64_t> last_imu_stamp_ns_;
};

}  // namespace lineloc
