// The measurements the inertial navigator (inertial_navigator.h) fuses
// besides the IMU: as the sensors give them (DGPS position and Doppler
// velocity, compass heading, and the backbone's vision fixes), as the filter
// holds them (navigation_filter.h: in the world frame, with the residual of
// their last update), and what became of each: its outcome, counted per
// sensor.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <variant>

#include "common/geometry/pose.h"

namespace lineloc {

struct GpsFix {
  int64_t stamp_ns = 0;
  Eigen::Vector3d p_world_antenna = Eigen::Vector3d::Zero();
  // The receiver's own word on the fix's error (gnss_error_model.h), per
  // horizontal axis and vertically (m); 0: the navigator's configured sigmas.
  double horizontal_sigma_m = 0.0;
  double vertical_sigma_m = 0.0;
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

// The counter of `outcome` in `counters`. Throws std::logic_error for
// kPending, which has none.
int64_t& counterOf(MeasurementCounters& counters, MeasurementOutcome outcome);

// A vision fix: the camera's pose and its covariance R, and U, the part of R
// its error shares with the fixes after it, levelled (correlated_fix_model.h).
struct VisionPayload {
  PoseWithCovariance T_world_camera;
  Matrix6d unproven_covariance = Matrix6d::Zero();
};
struct GpsPayload {
  Eigen::Vector3d p_world_antenna = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
};
struct GpsVelocityPayload {
  Eigen::Vector2d v_world_antenna_mps = Eigen::Vector2d::Zero();
};
// The compass's heading as the body's yaw in the world (site) frame.
struct YawPayload {
  double yaw_rad = 0.0;
};

using MeasurementPayload = std::variant<VisionPayload, GpsPayload, GpsVelocityPayload, YawPayload>;

// The sensor a measurement comes from, in the order of MeasurementPayload's alternatives.
enum class MeasurementKind { kVision, kGps, kGpsVelocity, kCompass };
inline constexpr size_t kMeasurementKinds = std::variant_size_v<MeasurementPayload>;

// A measurement as the filter holds it, with the outcome and residual of its
// last update (none while the IMU has not reached its time).
struct Measurement {
  explicit Measurement(MeasurementPayload payload_in) : payload(std::move(payload_in)) {}

  MeasurementPayload payload;
  std::optional<MeasurementOutcome> outcome;
  // A vision fix's residual z - h(x) against the filter.
  std::optional<Eigen::Matrix<double, 6, 1>> vision_residual;
  // A compass reading's yaw residual, likewise.
  std::optional<double> yaw_residual_rad;

  MeasurementKind kind() const { return static_cast<MeasurementKind>(payload.index()); }
};

}  // namespace lineloc
