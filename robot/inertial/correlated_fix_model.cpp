#include "robot/inertial/correlated_fix_model.h"

#include <algorithm>
#include <cmath>

#include "robot/inertial/measurement_models.h"

namespace lineloc {

Matrix6d levelFrameOffset(Matrix6d covariance) {
  for (const int tilt_axis : {3, 4}) {
    covariance.row(tilt_axis).setZero();
    covariance.col(tilt_axis).setZero();
  }
  return covariance;
}

CorrelatedFixModel::CorrelatedFixModel(const InertialNavigatorConfig& config)
    : correlation_m_(config.vision_error_correlation_m),
      correlation_rad_(config.vision_error_correlation_rad),
      shared_fraction_(config.shared_fix_error_fraction),
      shared_length_m_(config.shared_fix_error_length_m),
      T_body_camera_(config.T_body_camera) {}

double CorrelatedFixModel::inflation(const NavigationState& state,
                                     const FixCorrelation& last) const {
  if (!last.at_last_fix || correlation_m_ == 0.0) {
    return 1.0;
  }
  const NavigationState& at_fix = *last.at_last_fix;
  const double travel_m = (state.p_world_body - at_fix.p_world_body).norm();
  const double turn_rad = state.q_world_body.angularDistance(at_fix.q_world_body);
  const double rho = std::exp(-(travel_m / correlation_m_ + turn_rad / correlation_rad_));
  return std::min((1.0 + rho) / (1.0 - rho), kMaxInflation);
}

void CorrelatedFixModel::forget(const Eigen::Vector3d& p_world_body_before,
                                const Eigen::Vector3d& p_world_body_after,
                                const FixCorrelation& last, ErrorCovariance& covariance) const {
  if (shared_length_m_ == 0.0 || !last.at_last_fix) {
    return;
  }
  // rho_s^2 = exp(-2 d / L_s) at the distance d from the last applied fix.
  const auto correlationSquared = [&](const Eigen::Vector3d& p_world_body) {
    return std::exp(-2.0 * (p_world_body - last.at_last_fix->p_world_body).norm() /
                    shared_length_m_);
  };
  const double decorrelated = std::max(
      0.0, correlationSquared(p_world_body_before) - correlationSquared(p_world_body_after));
  setPoseBlock(poseBlock(covariance) + decorrelated * last.shared_fix_error, covariance);
}

void CorrelatedFixModel::recordApplied(const VisionPayload& fix, const NavigationState& state,
                                       double prior_position_variance,
                                       const ErrorCovariance& covariance,
                                       FixCorrelation& last) const {
  const Eigen::Isometry3d& T_world_camera = fix.T_world_camera.pose;
  const Matrix6d& R = fix.T_world_camera.covariance;
  last.at_last_fix = state;
  last.unproven_covariance =
      bodyPoseCovarianceOf(T_world_camera, fix.unproven_covariance, T_body_camera_);
  last.fix_offset_covariance =
      shared_fraction_ * bodyPoseCovarianceOf(T_world_camera, R, T_body_camera_);
  // The fix's share w of the state: the part of its position variance the
  // update took out.
  const double share = prior_position_variance > 0.0
                           ? std::clamp(1.0 - covariance.block<3, 3>(kPosition, kPosition).trace() /
                                                  prior_position_variance,
                                        0.0, 1.0)
                           : 0.0;
  last.shared_fix_error =
      (1.0 - share) * last.shared_fix_error +
      share * shared_fraction_ *
          bodyPoseCovarianceOf(T_world_camera, levelFrameOffset(R - fix.unproven_covariance),
                               T_body_camera_);
}

// Raising a principal block by a positive semi-definite amount keeps the
// whole positive semi-definite. A singular pose block (a state started as
// exactly known) has no covering; the sum, though looser, covers both.
ErrorCovariance CorrelatedFixModel::reported(ErrorCovariance covariance,
                                             const FixCorrelation& last) const {
  const Matrix6d pose = poseBlock(covariance) + last.unproven_covariance;
  const Matrix6d covering = coveringCovariance(pose, last.fix_offset_covariance);
  setPoseBlock(covering.allFinite() ? covering : pose + last.fix_offset_covariance, covariance);
  return covariance;
}

}  // namespace lineloc
