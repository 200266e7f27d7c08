#include "robot/inertial/navigation_filter.h"

#include "common/stats/chi_square.h"
#include "robot/inertial/error_state_update.h"
#include "robot/inertial/measurement_models.h"

namespace lineloc {
namespace {

MeasurementOutcome fromUpdate(UpdateStatus status) {
  switch (status) {
    case UpdateStatus::kAccepted:
      return MeasurementOutcome::kAccepted;
    case UpdateStatus::kGated:
      return MeasurementOutcome::kGated;
    case UpdateStatus::kDegenerate:
      return MeasurementOutcome::kDegenerate;
  }
  return MeasurementOutcome::kDegenerate;
}

// A bounding update that adds nothing is skipped.
MeasurementOutcome fromBoundingUpdate(const std::optional<UpdateOutcome>& outcome) {
  return outcome ? fromUpdate(outcome->status) : MeasurementOutcome::kSkipped;
}

}  // namespace

NavigationFilter::NavigationFilter(const InertialNavigatorConfig& config)
    : strapdown_(config.imu_noise, Eigen::Vector3d(0.0, 0.0, -config.gravity_mps2)),
      fixes_(config),
      T_body_camera_(config.T_body_camera),
      p_body_gps_antenna_(config.p_body_gps_antenna),
      gps_velocity_sigma_mps_(config.gps_velocity_sigma_mps),
      compass_yaw_sigma_rad_(compassYawSigma_rad(config)),
      zero_velocity_max_speed_mps_(config.zero_velocity_max_speed_mps),
      zero_velocity_sigma_mps_(config.zero_velocity_sigma_mps),
      zero_velocity_interval_ns_(config.zero_velocity_interval_ns) {
  for (size_t dimension = 1; dimension < gate_by_dimension_.size(); ++dimension) {
    gate_by_dimension_[dimension] =
        chiSquareQuantile(config.gate_probability, static_cast<double>(dimension));
  }
}

void NavigationFilter::propagate(const ImuSample& from, const ImuSample& to,
                                 FilterSnapshot& snapshot) const {
  const Eigen::Vector3d p_before = snapshot.state.p_world_body;
  strapdown_.propagate(from, to, snapshot.state, snapshot.covariance);
  fixes_.forget(p_before, snapshot.state.p_world_body, snapshot.fixes, snapshot.covariance);
}

MeasurementOutcome NavigationFilter::apply(Measurement& measurement, const ImuSample& imu,
                                           FilterSnapshot& snapshot) const {
  NavigationState& state = snapshot.state;
  ErrorCovariance& covariance = snapshot.covariance;
  if (const auto* vision = std::get_if<VisionPayload>(&measurement.payload)) {
    const LinearisedMeasurement<6> z =
        linearisePoseFix(state, vision->T_world_camera, T_body_camera_);
    measurement.vision_residual = z.residual;
    const Matrix6d update_noise =
        fixes_.inflation(state, snapshot.fixes) * (z.noise - vision->unproven_covariance);
    const double prior_position_variance = covariance.block<3, 3>(kPosition, kPosition).trace();
    const UpdateOutcome outcome =
        applyUpdate(z, gate_by_dimension_[6], state, covariance, update_noise);
    if (outcome.status == UpdateStatus::kAccepted) {
      snapshot.position_known = true;
      snapshot.velocity_known = true;
      fixes_.recordApplied(*vision, state, prior_position_variance, covariance, snapshot.fixes);
    }
    return fromUpdate(outcome.status);
  }
  if (const auto* gps = std::get_if<GpsPayload>(&measurement.payload)) {
    const std::optional<UpdateOutcome> outcome = applyBoundingUpdate(
        lineariseAntennaPosition(state, gps->p_world_antenna, gps->covariance, p_body_gps_antenna_),
        gate_by_dimension_[3], state, covariance);
    if (outcome && outcome->status == UpdateStatus::kAccepted) {
      snapshot.position_known = true;
    }
    return fromBoundingUpdate(outcome);
  }
  if (const auto* velocity = std::get_if<GpsVelocityPayload>(&measurement.payload)) {
    const UpdateOutcome outcome =
        applyUpdate(lineariseAntennaVelocity(state, imu.gyro_radps, velocity->v_world_antenna_mps,
                                             gps_velocity_sigma_mps_, p_body_gps_antenna_),
                    gate_by_dimension_[2], state, covariance);
    if (outcome.status == UpdateStatus::kAccepted) {
      snapshot.velocity_known = true;
    }
    return fromUpdate(outcome.status);
  }
  const auto& yaw = std::get<YawPayload>(measurement.payload);
  const auto z = lineariseYaw(state, yaw.yaw_rad, compass_yaw_sigma_rad_);
  if (!z) {
    return MeasurementOutcome::kDegenerate;
  }
  measurement.yaw_residual_rad = z->residual(0);
  return fromBoundingUpdate(applyBoundingUpdate(*z, gate_by_dimension_[1], state, covariance));
}

void NavigationFilter::updateZeroVelocity(const ImuSample& imu, bool still,
                                          FilterSnapshot& snapshot) const {
  const bool slow = snapshot.state.v_world_body.norm() < zero_velocity_max_speed_mps_;
  if (!still || !slow || !snapshot.velocity_known ||
      imu.stamp_ns - snapshot.last_zero_velocity_ns < zero_velocity_interval_ns_) {
    return;
  }
  const UpdateOutcome outcome =
      applyUpdate(lineariseZeroVelocity(snapshot.state, zero_velocity_sigma_mps_),
                  gate_by_dimension_[3], snapshot.state, snapshot.covariance);
  if (outcome.status == UpdateStatus::kAccepted) {
    snapshot.last_zero_velocity_ns = imu.stamp_ns;
    ++snapshot.zero_velocity_updates;
  }
}

ErrorCovariance NavigationFilter::reportedCovariance(const FilterSnapshot& snapshot) const {
  return fixes_.reported(snapshot.covariance, snapshot.fixes);
}

}  // namespace lineloc
