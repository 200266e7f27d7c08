// One step of the inertial navigator's 15-state error-state Kalman filter
// (strapdown.h, error_state_update.h), the arithmetic the measurement history
// (measurement_history.h) runs and replays: propagation between two IMU
// readings, the update with a measurement at its time, and zero-velocity
// updates.
//
// Updates (measurement_models.h). Vision pose fix (6-DoF, its own
// covariance, correlated with the fixes before it: correlated_fix_model.h);
// DGPS antenna position as a bound (applyBoundingUpdate): its errors are
// correlated over minutes, so repeated fixes add no information, and a
// vision-tracked pose must not be pulled by them; DGPS antenna velocity over
// ground (the Doppler's error is white, unlike the position's): it bounds the
// velocity, and so the drift, while vision has no fix, and keeps a quiet
// cruise from being held at zero by zero-velocity updates; compass yaw, as a
// bound too, its error shared by every reading (compass_bias_sigma_rad); zero
// velocity when the IMU is still and the estimated speed small. Each is gated
// by its normalised innovation squared at `gate_probability` of the
// chi-square distribution; a bounding update is gated before it is skipped,
// so a compass that disagrees counts as gated.
#pragma once

#include <array>
#include <cstdint>

#include "robot/inertial/correlated_fix_model.h"
#include "robot/inertial/imu_sample.h"
#include "robot/inertial/inertial_navigator_config.h"
#include "robot/inertial/navigation_state.h"
#include "robot/inertial/navigator_measurements.h"
#include "robot/inertial/strapdown.h"

namespace lineloc {

// The filter at an IMU sample.
struct FilterSnapshot {
  NavigationState state;
  ErrorCovariance covariance = ErrorCovariance::Identity();
  ImuSample imu;
  int64_t last_zero_velocity_ns = 0;
  int64_t zero_velocity_updates = 0;
  // False from a start without position until a DGPS or vision fix is accepted.
  bool position_known = true;
  // False from a start whose stillness only the IMU saw until a DGPS
  // velocity or vision fix is accepted: no zero-velocity updates until then.
  bool velocity_known = true;
  FixCorrelation fixes;
};

class NavigationFilter {
 public:
  explicit NavigationFilter(const InertialNavigatorConfig& config);

  // Propagates `snapshot` from reading `from` to `to` and forgets the share of
  // the fixes' shared error the step's travel decorrelates.
  void propagate(const ImuSample& from, const ImuSample& to, FilterSnapshot& snapshot) const;
  // Updates `snapshot` with `measurement` at `imu`, the reading at its time,
  // and records the measurement's residual.
  MeasurementOutcome apply(Measurement& measurement, const ImuSample& imu,
                           FilterSnapshot& snapshot) const;
  // A zero-velocity update at the sample `imu` when the IMU is `still`, the
  // speed below zero_velocity_max_speed_mps, the velocity known, and the last
  // one zero_velocity_interval_ns ago.
  void updateZeroVelocity(const ImuSample& imu, bool still, FilterSnapshot& snapshot) const;

  // The covariance the filter reports (CorrelatedFixModel::reported).
  ErrorCovariance reportedCovariance(const FilterSnapshot& snapshot) const;

 private:
  Strapdown strapdown_;
  CorrelatedFixModel fixes_;
  // The chi-square gate at gate_probability, by the measurement's dimension.
  std::array<double, 7> gate_by_dimension_{};
  Eigen::Isometry3d T_body_camera_;
  Eigen::Vector3d p_body_gps_antenna_;
  double gps_velocity_sigma_mps_;
  double compass_yaw_sigma_rad_;
  double zero_velocity_max_speed_mps_;
  double zero_velocity_sigma_mps_;
  int64_t zero_velocity_interval_ns_;
};

}  // namespace lineloc
