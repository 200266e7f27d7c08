#include "backbone/service/robot_session.h"

#include <utility>

namespace lineloc {

lineloc_msg_FixStatus toFixStatus(AlignmentStatus status) {
  switch (status) {
    case AlignmentStatus::kOk:
      return lineloc_msg_FIX_OK;
    case AlignmentStatus::kTooFewMatches:
      return lineloc_msg_FIX_TOO_FEW_MATCHES;
    case AlignmentStatus::kIllConditioned:
      return lineloc_msg_FIX_DEGENERATE;
    case AlignmentStatus::kAmbiguous:
      return lineloc_msg_FIX_AMBIGUOUS;
    case AlignmentStatus::kFailed:
    case AlignmentStatus::kInconsistent:
      return lineloc_msg_FIX_DIVERGED;
  }
  return lineloc_msg_FIX_INTERNAL_ERROR;
}

RobotSession::RobotSession(const RobotSessionOptions& options, const LocalizerOptions& localizer)
    : options_(options),
      localizer_(localizer),
      motion_(options.motion),
      fix_scatter_(options.fix_scatter),
      acquisition_(options.hypotheses),
      proof_(options.proof, localizer) {}

OdometryPose RobotSession::hear(const LineSetData& line_set) {
  return motion_.add(line_set.stamp_ns, line_set.predicted_T_world_camera);
}

PoseWithCovariance RobotSession::groundedPrior(const LineSetData& line_set,
                                               const PreparedMap& map) const {
  PoseWithCovariance prior = line_set.predicted_T_world_camera;
  const double ground_variance = options_.ground_level_sigma_m * options_.ground_level_sigma_m;
  const std::optional<double> ground_level =
      map.ground_level.at(prior.pose.translation().head<2>());
  if (line_set.camera_height_m <= 0.0 || !ground_level ||
      !(prior.covariance(2, 2) > ground_variance)) {
    return prior;
  }
  prior.pose.translation().z() = *ground_level + line_set.camera_height_m;
  prior.covariance.row(2).setZero();
  prior.covariance.col(2).setZero();
  prior.covariance(2, 2) = ground_variance;
  return prior;
}

PoseWithCovariance RobotSession::prior(const LineSetData& line_set, const PreparedMap& map) const {
  const PoseWithCovariance grounded = groundedPrior(line_set, map);
  const std::lock_guard<std::mutex> lock(proof_mutex_);
  return proof_.searchPrior(grounded);
}

RobotSession::FramePlan RobotSession::planFor(const LineSetData& line_set,
                                              const OdometryPose& odometry,
                                              const PreparedMap& map) const {
  const PoseWithCovariance grounded = groundedPrior(line_set, map);
  const std::lock_guard<std::mutex> lock(proof_mutex_);
  const PoseWithCovariance own = proof_.searchPrior(grounded);
  if (!needsAcquisition(own, localizer_)) {
    return {Plan::kTrack, own, 0.0};
  }
  if (const std::optional<PoseWithCovariance> carried =
          proof_.carriedStart(line_set.stamp_ns, odometry)) {
    return {Plan::kTrack, *carried, options_.carried_start_step_m};
  }
  return {Plan::kSearch, own, 0.0};
}

RobotSession::Answered RobotSession::answer(const LineSetData& line_set,
                                            const OdometryPose& odometry,
                                            const Localization& localization, PoseFixData& fix) {
  const Alignment& alignment = localization.alignment;
  fix.timings.visibility += localization.visibility_ns;
  fix.timings.matching = alignment.matching_ns;
  fix.timings.pose = alignment.pose_ns;
  fix.status = toFixStatus(alignment.status);
  fix.inliers = static_cast<uint32_t>(alignment.inliers);
  fix.residual_rms_px = static_cast<float>(alignment.rms_residual_px);
  if (alignment.status != AlignmentStatus::kOk) {
    return {};
  }
  fix.T_world_camera =
      fix_scatter_.floorAndAdd(line_set.stamp_ns, odometry, alignment.T_world_camera);
  TrackingProof::Unproven unproven;
  bool resumed = false;
  {
    const std::lock_guard<std::mutex> lock(proof_mutex_);
    if (offered_handover_) {
      resumed = proof_.resume(*offered_handover_, line_set.stamp_ns, odometry, fix.T_world_camera,
                              line_set.predicted_T_world_camera);
      offered_handover_.reset();
    }
    unproven = proof_.unprovenAt(line_set.stamp_ns, odometry, fix.T_world_camera);
  }
  if (unproven.offset) {
    fix.unproven_position_sigma_m = unproven.offset->position_m;
    fix.unproven_rotation_sigma_rad = unproven.offset->rotation_rad;
    fix.T_world_camera.covariance +=
        diagonalPoseCovariance(fix.unproven_position_sigma_m, fix.unproven_rotation_sigma_rad);
  }
  return {unproven.proof_due, unproven.started_from_prediction, resumed};
}

bool RobotSession::awaitsHandover() const {
  const std::lock_guard<std::mutex> lock(proof_mutex_);
  return !proof_.proven();
}

void RobotSession::offerHandover(const TrackingHandover& handover) {
  if (!handover.tracking && !handover.hypotheses.T_prediction_camera.empty()) {
    acquisition_.adopt(handover.hypotheses);
  }
  const std::lock_guard<std::mutex> lock(proof_mutex_);
  offered_handover_ = handover;
}

TrackingHandover RobotSession::handover(int64_t stamp_ns, const OdometryPose& odometry) const {
  TrackingHandover handover;
  {
    const std::lock_guard<std::mutex> lock(proof_mutex_);
    handover = proof_.handover(stamp_ns, odometry);
  }
  if (!handover.tracking) {
    handover.hypotheses = acquisition_.handed();
  }
  return handover;
}

AcquisitionSession::Searched RobotSession::search(const LineSetData& line_set,
                                                  const OdometryPose& odometry,
                                                  std::shared_ptr<const PreparedMap> map,
                                                  const PoseWithCovariance& prior,
                                                  const LocalizerOptions& options) {
  AcquisitionSession::Searched searched =
      acquisition_.search(line_set, odometry, std::move(map), prior, options);
  if (searched.decision) {
    {
      const std::lock_guard<std::mutex> lock(proof_mutex_);
      proof_.startFromSearch(line_set.stamp_ns, odometry, *searched.decision);
    }
    acquisition_.clear();
  }
  return searched;
}

RobotSession::Proved RobotSession::prove(const LineSetData& line_set, const PreparedMap& map,
                                         const Eigen::Isometry3d& tracked,
                                         const ProofRequest& request,
                                         const LocalizerOptions& options) {
  const PoseWithCovariance prior = proof_.proofPrior(tracked, options_.ground_level_sigma_m);
  Proved proved;
  proved.localization = localize(line_set.segments, line_set.corners, map.segments, map.scene,
                                 prior, line_set.camera, options);
  proved.verdict = judgeProof(line_set, map, tracked, proved.localization, options.acquisition,
                              proof_.agreement());
  const std::lock_guard<std::mutex> lock(proof_mutex_);
  proved.applied = proof_.apply(proved.verdict, request);
  return proved;
}

std::optional<Eigen::Vector3d> RobotSession::positionAhead(const LineSetData& line_set,
                                                           double lookahead_s) {
  const Eigen::Vector3d position = line_set.predicted_T_world_camera.pose.translation();
  std::optional<Eigen::Vector3d> ahead;
  if (last_position_ && line_set.stamp_ns > last_position_->stamp_ns) {
    const double dt_s = (line_set.stamp_ns - last_position_->stamp_ns) * 1e-9;
    ahead = position + (position - last_position_->position) / dt_s * lookahead_s;
  }
  last_position_ = StampedPosition{line_set.stamp_ns, position};
  return ahead;
}

}  // namespace lineloc
