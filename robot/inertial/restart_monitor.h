// When the measurements keep contradicting the navigation filter, the filter
// is wrong, not they: the restarts it then takes.
//
// Restart from vision. Vision fixes gated without a break for
// `vision_gated_restart_after_ns` mean the filter, not the fixes, is wrong,
// but only when their residuals against the filter move together: position
// residuals r_i = a + b (t_i - t_mean) + e_i (least squares), attitude
// residuals theta_i = theta_mean + e_i, each e_i within the gate of its own
// fix's covariance. The filter then restarts at the newest fix's pose
// (startup_alignment.h) with its own velocity plus the drift b; the IMU
// biases start again as at power-on. A burst of wrong fixes is shorter than
// that, and a backbone switching between two wrong solutions breaks the
// common offset.
//
// Heading restart. A heading started from a compass disturbed over the whole
// start-up window (a robot parked beside a car) is precise and wrong.
// Compass readings gated without a break for `compass_gated_restart_after_ns`,
// with no vision fix applied meanwhile, whose residuals agree on one offset
// (their robust mean, robust_heading.h, holding kMinAgreeingCompassFraction
// of them), turn the filter's heading and velocity by that offset and give
// the yaw its start-up sigma again. Only readings that left the history
// count: their outcomes are final.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "robot/inertial/inertial_navigator_config.h"
#include "robot/inertial/measurement_history.h"
#include "robot/inertial/navigation_filter.h"
#include "robot/inertial/navigator_measurements.h"
#include "robot/inertial/startup_alignment.h"

namespace lineloc {

// A gated vision fix with its residual z - h(x) against the filter.
struct GatedFix {
  int64_t stamp_ns = 0;
  const VisionPayload* vision = nullptr;
  Eigen::Matrix<double, 6, 1> residual = Eigen::Matrix<double, 6, 1>::Zero();
};

// What a run of gated fixes has in common against the filter.
struct ResidualDrift {
  Eigen::Vector3d velocity_mps = Eigen::Vector3d::Zero();  // b
  // Of each axis of b: the largest position variance of a fix over
  // sum_i (t_i - t_mean)^2.
  double velocity_variance = 0.0;
  Eigen::Vector3d attitude_offset_rad = Eigen::Vector3d::Zero();  // theta_mean
};

// The drift of `run`'s residuals; nullopt when a fix's position or attitude
// error e_i lies beyond `gate` (the chi-square gate of 3 degrees of freedom)
// of its covariance. `run` holds at least two fixes of different times.
std::optional<ResidualDrift> commonResidualDrift(const std::vector<GatedFix>& run, double gate);

// A restart from vision: the fix and the velocity to start from.
struct VisionRestart {
  BodyFix fix;
  StartVelocity velocity;
};

class VisionRestartMonitor {
 public:
  explicit VisionRestartMonitor(const InertialNavigatorConfig& config);

  // A restart when the vision fixes in `history` gated since the last one
  // not gated span vision_gated_restart_after_ns, are at least
  // kMinGatedFixesForRestart, and drift together (commonResidualDrift).
  std::optional<VisionRestart> restart(const MeasurementHistory& history) const;

 private:
  // The gated fixes since the last one not gated, newest first, when they
  // span restart_after_ns_; else empty.
  std::vector<GatedFix> gatedRun(const MeasurementHistory& history) const;

  int64_t restart_after_ns_;
  double gate_;
  double gravity_mps2_;
  Eigen::Isometry3d T_body_camera_;
};

class CompassRestartMonitor {
 public:
  explicit CompassRestartMonitor(const InertialNavigatorConfig& config);

  // A measurement that left the history: a gated compass reading extends the
  // run, an accepted reading or vision fix ends it.
  void add(int64_t stamp_ns, const Measurement& measurement);
  void clear() { gated_.clear(); }

  // The heading restart from the filter's `latest` snapshot when the run
  // spans compass_gated_restart_after_ns and agrees on its offset; a run that
  // spans it but does not agree slides on, its oldest reading dropped.
  std::optional<NavigatorStart> restart(const FilterSnapshot& latest);

 private:
  struct GatedYaw {
    int64_t stamp_ns = 0;
    double residual_rad = 0.0;
  };

  int64_t restart_after_ns_;
  double gate_rad_;
  double yaw_sigma_rad_;
  // Gated compass readings since the last accepted one or vision fix, oldest first.
  std::vector<GatedYaw> gated_;
};

}  // namespace lineloc
