// Onboard inertial navigation (paper §1.2): a strapdown IMU carries the pose
// between fixes; the backbone's vision fixes correct its drift; DGPS and the
// compass start it. A 15-state error-state Kalman filter (strapdown.h,
// error_state_update.h) runs at IMU rate.
//
// Late fixes. Every IMU sample leaves a snapshot (state, covariance, sample) in
// a history of `history_ns`; every measurement is kept, in time order, for as
// long as its time is inside that history. A measurement whose time is already
// past rewinds to the last snapshot before it and replays the IMU samples and
// measurements after it, splitting the IMU interval at each measurement's time
// (rates interpolated linearly). A measurement whose time is still ahead waits
// until the IMU reaches it. Both paths run the same arithmetic, so a fix
// delivered 300 ms late gives the same state as one delivered on time.
//
// Start-up, standing. Standing still for `alignment.window_ns` gives roll,
// pitch and gyro bias (stillness_detector.h); the compass, corrected for
// magnetic declination and meridian convergence, gives yaw, the robust mean of
// the window's readings (robust_heading.h: a disturbance over part of the
// window is left out); DGPS gives position; all with large covariances; only
// if the robot has not moved since power-on. Without a DGPS fix by the end of
// that window the filter starts all the same, its position unknown
// (kUnknownPositionSigma_m), and the first DGPS or vision fix accepted gives
// it; until then predictAt, state and health say "initialising": a prediction
// with no position would send the backbone's search to the wrong street.
// Such a start, which only the IMU calls still, may be a cruise as quiet as a
// standstill: it takes the velocity as unknown (sigma max_ground_speed_mps)
// and the gyro bias within its turn-on spread, and holds zero-velocity
// updates off until a DGPS velocity or a vision fix is accepted.
//
// Start-up, moving. A robot that has moved since power-on (started while
// driving, or whose software restarted mid-drive) starts from two consecutive
// DGPS velocities (the receiver's Doppler, NMEA RMC) at most
// kMaxVelocityMatchingBaseline_ns apart: roll and pitch by velocity matching
// against the IMU between them, yaw from the compass readings between them
// (in_motion_alignment.h); velocity the receiver's, the vertical one zero
// within a steep street's grade times the speed; position the DGPS fix of the
// same epoch, or unknown as above; gyro and accelerometer biases zero within
// their turn-on spread.
//
// DGPS velocities. Before a start, two consecutive ones beyond
// kMovingSpeedSigmas of their noise say the robot moves and bar the
// standstill start; one alone may be multipath (a signal reflected off a
// façade throws the Doppler by a metre per second): it holds the standstill
// start until the next epoch confirms or denies it, and a denied one is
// counted gated. After the start each one updates the filter as the
// antenna's horizontal velocity over ground (measurement_models.h; the
// Doppler's error is white, unlike the position's): that bounds the velocity,
// and so the drift, while vision has no fix, and keeps a quiet cruise from
// being held at zero by zero-velocity updates.
//
// Vision fixes before any start (the window not yet full, or a robot that
// never stood still and has no DGPS velocity) start the filter from their
// pose: at once when it has stood still since power-on, else from two fixes
// at most 0.5 s apart, whose difference gives the velocity.
//
// Restart. Vision fixes gated without a break for
// `vision_gated_restart_after_ns` mean the filter, not the fixes, is wrong,
// but only when their residuals against the filter move together: position
// residuals a + b t and attitude residuals a constant, each fix within its own
// covariance's gate. The filter then restarts at the newest fix's pose with
// its own velocity plus the drift b; the IMU biases start again as at
// power-on. A burst of wrong fixes is shorter than that, and a backbone
// switching between two wrong solutions breaks the common offset.
//
// Heading restart. A heading started from a compass disturbed over the whole
// start-up window (a robot parked beside a car) is precise and wrong.
// Compass readings gated without a break for `compass_gated_restart_after_ns`,
// with no vision fix applied meanwhile, whose residuals agree on one offset
// (their robust mean holding kMinAgreeingCompassFraction of them), turn the
// filter's heading and velocity by that offset and give the yaw its start-up
// sigma again. Only readings that left the history count: their outcomes are
// final.
//
// Fixes of an unchanged view. A vision fix shares its error with the fixes
// of a similar view: the same edges, matched the same way. The error is
// modelled as a first-order Gauss-Markov process in the camera's motion,
// rho = exp(-(|dp| / L_p + |dtheta| / L_theta)) between a fix and the last
// one applied; each fix updates with its covariance times (1 + rho) /
// (1 - rho), the factor by which N samples of such a process tell less than
// N independent ones (the variance of their mean is sigma^2 (1 + rho) /
// ((1 - rho) N)), and is gated with its covariance as it is. L_p and
// L_theta are a centimetre and a tenth of a degree: a standing robot's fixes
// count once, a moving robot's nearly fully. Fixes share part of their error
// over metres of travel too, so the covariance the filter reports (state,
// health) is never less than f = shared_fix_error_fraction of the last
// applied fix's: the share of a fix's error no run of fixes averages away;
// the tilt likewise, which gravity bounds only to an accelerometer bias over
// g. The filter's own covariance, its updates and the predictions for the
// backbone keep the model above.
//
// Forgetting the shared error (off by default: shared_fix_error_length_m 0).
// The shared error b is a first-order Gauss-Markov process in travel,
// b' = rho_s b + w, rho_s = exp(-d / L_s), Var(w) = (1 - rho_s^2) f (R - U).
// The filter estimates the pose in the fixes' frame, the truth plus b, so as
// it moves d from the last applied fix its pose covariance grows by
// (1 - rho_s^2) S, S the variance of the shared error the state holds: each
// applied fix, of covariance R, takes a share w of it, S = (1 - w) S +
// w f (R - U), level part, w the part of the position variance its update
// took out.
//
// Unproven fixes. A fix tracked from a pose the backbone has not yet proven
// (tracking_proof.h) carries an unproven part U of its covariance R: an
// offset its error shares with every fix after it until proven, not noise
// on each. As in a Schmidt-Kalman filter's "consider" state o ~ N(0, U) in
// z = h(x) + o + v, the filter estimates the pose relative to the fixes'
// frame: it gates a fix with R, so a fix whose offset moved within U still
// passes; updates with R - U, what tracking measured, so the fixes' motion
// and drift count in full; and adds the last applied fix's U to the
// covariance it reports (state, health). The tilt part of U stays noise on
// each fix: a frame tilted against gravity is no frame the IMU moves in. The
// predictions for the backbone (predictAt) leave U out: the backbone tracks
// in the frame its own fixes define and proves that frame itself.
//
// Updates. Vision pose fix (6-DoF, its own covariance); DGPS antenna position
// as a bound (applyBoundingUpdate, error_state_update.h): its errors are
// correlated over minutes, so repeated fixes add no information, and a
// vision-tracked pose must not be pulled by them; compass yaw, as a bound too,
// its error shared by every reading (compass_bias_sigma_rad); zero velocity
// when the IMU is still and the estimated speed small. Each is gated by its
// normalised innovation squared at `gate_probability` of the chi-square
// distribution; rejections are counted in health().
//
// Bad input (non-finite or saturated IMU samples, time going backwards,
// duplicate stamps, invalid fixes) is dropped and counted; IMU gaps are
// propagated across and counted.
#pragma once

#include <array>
#include <cmath>
#include <deque>
#include <map>
#include <optional>
#include <variant>
#include <vector>

#include "common/geometry/pose.h"
#include "robot/inertial/error_state_update.h"
#include "robot/inertial/imu_sample.h"
#include "robot/inertial/navigation_state.h"
#include "robot/inertial/stillness_detector.h"
#include "robot/inertial/strapdown.h"

namespace lineloc {

struct InertialNavigatorConfig {
  ImuNoiseDensities imu_noise;
  double gravity_mps2 = 9.80665;
  // Samples beyond the IMU's range are saturated, hence wrong (ADIS16448: ±1000 deg/s, ±18 g).
  double gyro_range_radps = 17.45;
  double accel_range_mps2 = 176.5;
  int64_t imu_gap_ns = 20'000'000;
  // Rotation from the IMU's frame to the body frame, applied to every sample
  // (the lever arm's centripetal terms are neglected: small on a ground robot).
  Eigen::Matrix3d R_body_imu = Eigen::Matrix3d::Identity();
  // Camera mounted looking forward: camera z = body x, camera x = -body y, camera y = -body z.
  Eigen::Isometry3d T_body_camera = defaultBodyCamera();
  Eigen::Vector3d p_body_gps_antenna = Eigen::Vector3d::Zero();
  // Long enough for a fix found by the backbone's search from a DGPS start,
  // which answers its frame a second or two late.
  int64_t history_ns = 3'000'000'000;
  double gate_probability = 0.999;

  // Still: per-axis standard deviations within twice the white noise of one
  // sample (ADIS16448 at 200 Hz: 0.0024 rad/s, 0.028 m/s^2). Looser thresholds
  // let a robot that is pulling away at a few cm/s pass for standing.
  StillnessThresholds alignment{2'000'000'000, 0.005, 0.056};
  StillnessThresholds zero_velocity{500'000'000, 0.005, 0.056};
  double zero_velocity_max_speed_mps = 0.1;
  // The fastest the robot drives: the velocity sigma of a start whose
  // stillness only the IMU saw (see above).
  double max_ground_speed_mps = 3.0;
  // Covers the speed a trailing window misses when the robot pulls away (a few
  // cm/s).
  double zero_velocity_sigma_mps = 0.05;
  int64_t zero_velocity_interval_ns = 100'000'000;

  double gps_horizontal_sigma_m = 5.0;
  double gps_vertical_sigma_m = 10.0;
  // Per horizontal axis, of one DGPS velocity (Doppler: 0.05 m/s on a current
  // single-frequency receiver's data sheet, doubled for multipath in a street).
  double gps_velocity_sigma_mps = 0.1;
  // A compass reading's error: white noise from reading to reading, and an
  // error all readings share (calibration, mounting, the magnetic field of
  // the street), which no number of readings averages away. Each reading
  // bounds the yaw at sigma_c = hypot(white, shared) rather than shrinking it
  // (see Updates above), and a start from the compass has that yaw sigma.
  double compass_sigma_rad = 2.0 * M_PI / 180.0;
  double compass_bias_sigma_rad = 2.0 * M_PI / 180.0;
  double magnetic_declination_rad = 0.0;  // magnetic north's bearing from true north, east positive
  double grid_bearing_of_true_north_rad = 0.0;  // SiteProjection::gridBearingOfTrueNorth_rad
  double gyro_turn_on_bias_sigma_radps = 0.0035;
  double accel_turn_on_bias_sigma_mps2 = 0.05;

  // Compass readings gated without a break for this long, agreeing on one
  // offset from the filter's heading, with no vision fix applied, restart the
  // heading from them (0: never). Longer than a disturbance lasts (steel, a
  // passing car: seconds); the simulator's last 2-6 s.
  int64_t compass_gated_restart_after_ns = 8'000'000'000;

  // Vision fixes gated without a break for this long, moving together, restart
  // the filter from the newest (0: never).
  int64_t vision_gated_restart_after_ns = 1'000'000'000;

  // Correlation lengths of the vision fixes' error in travel and in turn
  // (L_p, L_theta above); 0: independent fixes.
  double vision_error_correlation_m = 0.01;
  double vision_error_correlation_rad = 0.1 * M_PI / 180.0;
  // Fraction f of a fix's covariance its error shares with the fixes around it
  // over metres of travel, below which the reported covariance does not fall
  // (see above); 0: independent fixes.
  double shared_fix_error_fraction = 0.5;
  // Correlation length L_s of that shared error in travel, over which the
  // filter forgets it (see above); 0: never.
  double shared_fix_error_length_m = 0.0;

  int64_t tracking_timeout_ns = 1'000'000'000;
  double lost_position_sigma_m = 10.0;

  static Eigen::Isometry3d defaultBodyCamera();
};

struct GpsFix {
  int64_t stamp_ns = 0;
  Eigen::Vector3d p_world_antenna = Eigen::Vector3d::Zero();
};

// The antenna's horizontal velocity over ground, site x (east) and y (north),
// from the receiver's Doppler measurements (NMEA RMC speed and course).
struct GpsVelocity {
  int64_t stamp_ns = 0;
  Eigen::Vector2d v_world_mps = Eigen::Vector2d::Zero();
};

// Magnetic heading of the body x axis, clockwise from magnetic north.
struct CompassReading {
  int64_t stamp_ns = 0;
  double magnetic_heading_rad = 0.0;
};

// kPending: ahead of the IMU, decided (and counted) when the IMU reaches its time.
enum class MeasurementOutcome {
  kAccepted,
  kGated,
  kDegenerate,
  kSkipped,
  kTooLate,
  kInvalid,
  kPending
};

struct MeasurementCounters {
  int64_t accepted = 0;
  int64_t gated = 0;
  int64_t degenerate = 0;
  int64_t skipped = 0;   // DGPS or compass while the estimate is better than it
  int64_t too_late = 0;  // older than the history, or than the start
  int64_t invalid = 0;   // non-finite, or a covariance that is not positive definite
  int64_t rejected() const { return gated + degenerate + too_late + invalid; }
};

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
  // shares with the fixes after it (see above); within it, else kInvalid.
  MeasurementOutcome applyVisionFix(int64_t stamp_ns, const PoseWithCovariance& T_world_camera,
                                    const Matrix6d& unproven_covariance = Matrix6d::Zero());

  // Starts the filter from a known state at a time the IMU samples given so far
  // cover. Returns false (and does nothing) when they do not.
  bool initialise(const NavigationState& state, const ErrorCovariance& covariance);

  // T_world_camera and its covariance at `stamp_ns` (a frame's exposure time),
  // using the configured T_body_camera; beyond the last IMU sample the last
  // rates are held. The covariance leaves the fixes' unproven part out (see
  // above). kNotInitialised also where the position was not yet known.
  PosePrediction predictAt(int64_t stamp_ns) const;
  // The state after the last IMU sample, with the covariance the filter
  // reports (the unproven offset and the fixes' shared error in it, see
  // above); nullopt before initialisation, or while the position is unknown.
  std::optional<NavigatorEstimate> state() const;
  // The camera's pose and covariance in `estimate` (state()'s), through the
  // configured T_body_camera.
  PoseWithCovariance cameraPose(const NavigatorEstimate& estimate) const;
  NavigatorHealth health() const;

 private:
  struct VisionPayload {
    PoseWithCovariance T_world_camera;
    Matrix6d unproven_covariance;
  };
  struct GpsPayload {
    Eigen::Vector3d p_world_antenna;
  };
  struct GpsVelocityPayload {
    Eigen::Vector2d v_world_antenna_mps;
  };
  struct YawPayload {
    double yaw_rad;
  };
  struct Measurement {
    std::variant<VisionPayload, GpsPayload, GpsVelocityPayload, YawPayload> payload;
    std::optional<MeasurementOutcome> outcome;
    // A vision fix's residual z - h(x) against the filter when last applied.
    std::optional<Eigen::Matrix<double, 6, 1>> vision_residual;
    // A compass reading's yaw residual, likewise.
    std::optional<double> yaw_residual_rad;
  };
  struct Snapshot {
    NavigationState state;
    ErrorCovariance covariance;
    ImuSample imu;
    int64_t last_zero_velocity_ns = 0;
    int64_t zero_velocity_updates = 0;
    // False from a start without position until a DGPS or vision fix is accepted.
    bool position_known = true;
    // False from a start whose stillness only the IMU saw until a DGPS
    // velocity or vision fix is accepted: no zero-velocity updates until then.
    bool velocity_known = true;
    // The state the last vision fix applied left.
    std::optional<NavigationState> at_last_vision;
    // That fix's unproven covariance, of the body's pose error [dp; dtheta].
    Matrix6d unproven_covariance = Matrix6d::Zero();
    // That fix's covariance, likewise, times shared_fix_error_fraction: the
    // least the filter reports (see above).
    Matrix6d fix_offset_covariance = Matrix6d::Zero();
    // S, the fixes' shared error the state holds (see above).
    Matrix6d shared_fix_error = Matrix6d::Zero();
  };
  struct BufferedImu {
    ImuSample sample;
    bool still = false;
  };
  static const ImuSample& sampleOf(const BufferedImu& buffered) { return buffered.sample; }
  // A vision fix as the body's pose, the covariance of what tracking measured
  // (R - U) and the unproven part U.
  struct BodyFix {
    int64_t stamp_ns = 0;
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    Matrix6d covariance = Matrix6d::Identity();
    Matrix6d unproven_covariance = Matrix6d::Zero();
  };
  // A gated vision fix in measurements_, with its residual against the filter.
  struct GatedFix {
    int64_t stamp_ns = 0;
    const VisionPayload* vision = nullptr;
    Eigen::Matrix<double, 6, 1> residual;
  };
  struct ResidualDrift {
    Eigen::Vector3d velocity_mps;
    double velocity_variance = 0.0;
    Eigen::Vector3d attitude_offset_rad;
  };
  // A gated compass reading whose outcome is final (it left the history).
  struct GatedYaw {
    int64_t stamp_ns = 0;
    double residual_rad = 0.0;
  };
  struct StartVelocity {
    Eigen::Vector3d v_world_mps;
    double sigma_mps = 0.0;
  };

  bool acceptImu(const ImuSample& sample);
  MeasurementOutcome addMeasurement(int64_t stamp_ns, Measurement measurement);
  void replayFrom(size_t snapshot_index);
  void process(const BufferedImu& imu);
  // Propagates `snapshot` from reading `from` to `to` and grows its pose
  // covariance by the share of the fixes' shared error the step's travel
  // decorrelates (see above).
  void propagate(const ImuSample& from, const ImuSample& to, Snapshot& snapshot) const;
  // `imu`: the reading at the measurement's time.
  MeasurementOutcome apply(Measurement& measurement, const ImuSample& imu,
                           Snapshot& snapshot) const;
  void recordOutcome(Measurement& measurement, MeasurementOutcome outcome);
  MeasurementCounters& countersFor(const Measurement& measurement);
  void prune();

  std::optional<ImuSample> bufferedImuAt(int64_t stamp_ns) const;
  // What a start knows of the position: nothing yet, a sensor's, or a vision
  // fix's, which counts as applied.
  enum class StartPosition { kUnknown, kFromSensors, kFromVision };
  void startAt(const NavigationState& state, const ErrorCovariance& covariance,
               const ImuSample& imu, StartPosition position,
               const Matrix6d& unproven_covariance = Matrix6d::Zero(), bool velocity_known = true);
  // (1 + rho) / (1 - rho) for a fix at the snapshot's state.
  double correlatedFixInflation(const Snapshot& snapshot) const;
  void tryInitialiseFromSensors();
  void tryInitialiseInMotion();
  // A start's position: `fix`'s antenna moved to the body at the state's
  // attitude, with DGPS's sigma; without a fix, unknown (kUnknownPositionSigma_m).
  // Returns the sigma per axis.
  Eigen::Vector3d placeAtDgps(const GpsFix* fix, NavigationState& state) const;
  // A speed beyond kMovingSpeedSigmas of the DGPS velocity's noise.
  bool isMotion(const GpsVelocity& velocity) const;
  // Before a start, the newest DGPS velocity claims motion that no later
  // epoch has confirmed or denied yet (see the header).
  bool motionClaimed() const;
  // Moved since power-on, or a DGPS velocity says so unconfirmed.
  bool mayHaveMoved() const;
  BodyFix bodyFixOf(int64_t stamp_ns, const VisionPayload& vision) const;
  // A covariance of the camera pose's error [dp; dtheta] as the body pose's.
  Matrix6d bodyCovarianceOf(const Eigen::Isometry3d& T_world_camera,
                            const Matrix6d& camera_covariance) const;
  // Standing still since power-on: zero; else from the fix and one at most
  // kMaxVelocityBaseline_ns before it (none: nullopt).
  std::optional<StartVelocity> startVelocity(const BodyFix& fix,
                                             const std::optional<BodyFix>& previous) const;
  // Starts at the fix's pose and covariance with this velocity, the IMU biases
  // from standing still or their turn-on spread.
  MeasurementOutcome startFromVision(const BodyFix& fix, const StartVelocity& velocity);
  // The gated vision fixes since the last one not gated, newest first, when they
  // span vision_gated_restart_after_ns; else empty.
  std::vector<GatedFix> gatedVisionRun() const;
  std::optional<ResidualDrift> commonResidualDrift(const std::vector<GatedFix>& run) const;
  void restartIfVisionKeepsBeingGated();
  // Extends or ends the run of gated compass readings with a measurement
  // leaving the history: a gated reading extends it, an accepted reading or
  // vision fix ends it.
  void trackGatedCompass(int64_t stamp_ns, const Measurement& measurement);
  void restartHeadingIfCompassKeepsBeingGated();
  // The gyro bias of the last still window when `stood_still` says the robot
  // stood there, else zero within its turn-on spread: a window only the IMU
  // calls still may be a cruise on a changing grade, whose mean rate is the
  // body pitching, not the bias.
  Eigen::Vector3d initialGyroBias(bool stood_still, double& sigma_radps) const;
  double yawFromCompass(double magnetic_heading_rad) const;
  // sigma_c = hypot(compass_sigma_rad, compass_bias_sigma_rad).
  double compassYawSigma_rad() const;

  InertialNavigatorConfig config_;
  Strapdown strapdown_;
  std::array<double, 7> gate_by_dimension_{};
  StillnessDetector alignment_detector_;
  StillnessDetector zero_velocity_detector_;
  // Gated compass readings since the last accepted one or vision fix, oldest first.
  std::vector<GatedYaw> gated_compass_;
  std::optional<StaticAlignment> alignment_;

  std::deque<BufferedImu> imu_;
  std::deque<Snapshot> snapshots_;
  std::multimap<int64_t, Measurement> measurements_;
  std::optional<GpsFix> startup_gps_;
  // The last two DGPS velocities before a start, oldest first.
  std::deque<GpsVelocity> startup_velocities_;
  std::deque<CompassReading> startup_compass_;
  std::optional<BodyFix> startup_vision_;
  bool moved_since_start_ = false;

  NavigatorHealth counters_;
  std::optional<int64_t> last_imu_stamp_ns_;
};

}  // namespace lineloc
