// The correlated error of the backbone's vision fixes, as the navigation
// filter (navigation_filter.h) takes it: the noise a fix updates the filter
// with, the covariance the filter reports, and how it forgets what a run of
// fixes shared (error_state_update.h: gated with R, updated with R_u).
//
// Fixes of an unchanged view. A vision fix shares its error with the fixes of
// a similar view: the same edges, matched the same way. The error is modelled
// as a first-order Gauss-Markov process in the camera's motion,
//   rho = exp(-(|dp| / L_p + |dtheta| / L_theta))
// between a fix and the last one applied; each fix updates with its
// covariance times (1 + rho) / (1 - rho), the factor by which N samples of
// such a process tell less than N independent ones (the variance of their
// mean is sigma^2 (1 + rho) / ((1 - rho) N)), and is gated with its
// covariance as it is. L_p and L_theta are a centimetre and a tenth of a
// degree: a standing robot's fixes count once, a moving robot's nearly fully.
//
// Shared fix error. Fixes share part of their error over metres of travel
// too, so the covariance the filter reports is never less than
// f = shared_fix_error_fraction of the last applied fix's R: the share of a
// fix's error no run of fixes averages away; the tilt likewise, which gravity
// bounds only to an accelerometer bias over g. The filter's own covariance,
// its updates and its predictions keep the model above.
//
// Forgetting the shared error (off by default: L_s = shared_fix_error_length_m
// 0). The shared error b is a first-order Gauss-Markov process in travel,
//   b' = rho_s b + w,  rho_s = exp(-d / L_s),  Var(w) = (1 - rho_s^2) f (R - U).
// The filter estimates the pose in the fixes' frame, the truth plus b, so as
// it moves d from the last applied fix its pose covariance grows by
// (1 - rho_s^2) S, S the variance of the shared error the state holds: each
// applied fix takes a share w of it,
//   S = (1 - w) S + w f (R - U), level part,
// w the part of the position variance its update took out.
//
// Unproven fixes. A fix tracked from a pose the backbone has not yet proven
// (tracking_proof.h) carries an unproven part U of its covariance R: an
// offset its error shares with every fix after it until proven, not noise on
// each. As in a Schmidt-Kalman filter's "consider" state o ~ N(0, U) in
// z = h(x) + o + v, the filter estimates the pose relative to the fixes'
// frame: it gates a fix with R, so a fix whose offset moved within U still
// passes; updates with R - U, what tracking measured, so the fixes' motion and
// drift count in full; and adds the last applied fix's U to the covariance it
// reports. The tilt part of U stays noise on each fix (levelFrameOffset): a
// frame tilted against gravity is no frame the IMU moves in. The predictions
// for the backbone leave U out: the backbone tracks in the frame its own
// fixes define and proves that frame itself.
#pragma once

#include <Eigen/Geometry>
#include <optional>

#include "common/geometry/pose.h"
#include "robot/inertial/inertial_navigator_config.h"
#include "robot/inertial/navigation_state.h"
#include "robot/inertial/navigator_measurements.h"

namespace lineloc {

// What the last vision fix applied left in the filter, body pose errors
// [dp; dtheta] throughout.
struct FixCorrelation {
  // The state its update left.
  std::optional<NavigationState> at_last_fix;
  // Its unproven covariance U.
  Matrix6d unproven_covariance = Matrix6d::Zero();
  // Its covariance times f: the least the filter reports.
  Matrix6d fix_offset_covariance = Matrix6d::Zero();
  // S, the fixes' shared error the state holds.
  Matrix6d shared_fix_error = Matrix6d::Zero();
};

// The part of a fix's covariance (camera pose error [dp; dtheta], dtheta in
// the world frame) the filter takes as an offset of the fixes' frame: all but
// the tilt (rotation about the world's horizontal axes), which gravity makes
// observable to the accelerometers and which stays noise on each fix.
Matrix6d levelFrameOffset(Matrix6d covariance);

class CorrelatedFixModel {
 public:
  // Takes L_p, L_theta, f, L_s and T_body_camera.
  explicit CorrelatedFixModel(const InertialNavigatorConfig& config);

  // (1 + rho) / (1 - rho) for a fix at `state`, at most kMaxInflation; 1
  // before any fix is applied, and for independent fixes (L_p = 0).
  double inflation(const NavigationState& state, const FixCorrelation& last) const;

  // Grows the pose block of `covariance` by (rho_s^2(d_before) -
  // rho_s^2(d_after)) S as the body moves from `p_world_body_before` to
  // `p_world_body_after`, d the distance from the last applied fix; nothing
  // when L_s = 0.
  void forget(const Eigen::Vector3d& p_world_body_before, const Eigen::Vector3d& p_world_body_after,
              const FixCorrelation& last, ErrorCovariance& covariance) const;

  // Records in `last` that `fix` was applied: its update took the state to
  // `state` and the covariance's position block from a trace of
  // `prior_position_variance` to that of `covariance`.
  void recordApplied(const VisionPayload& fix, const NavigationState& state,
                     double prior_position_variance, const ErrorCovariance& covariance,
                     FixCorrelation& last) const;

  // The covariance the filter reports: `covariance`, of the pose relative to
  // the fixes' frame, plus the unproven offset U of that frame, covering f R.
  ErrorCovariance reported(ErrorCovariance covariance, const FixCorrelation& last) const;

  // A fix of an unchanged view still counts, at a ten-thousandth of an independent one.
  static constexpr double kMaxInflation = 1e4;

 private:
  double correlation_m_;
  double correlation_rad_;
  double shared_fraction_;
  double shared_length_m_;
  Eigen::Isometry3d T_body_camera_;
};

}  // namespace lineloc
