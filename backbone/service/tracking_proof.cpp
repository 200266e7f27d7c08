#include "backbone/service/tracking_proof.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace lineloc {

namespace {

// The poses a search found: its best, and an ambiguous search's rival too.
std::vector<Eigen::Isometry3d> foundPoses(const Localization& found) {
  std::vector<Eigen::Isometry3d> poses{found.alignment.T_world_camera.pose};
  if (found.alignment.status == AlignmentStatus::kAmbiguous && found.search &&
      found.search->T_world_camera_rival) {
    poses.push_back(*found.search->T_world_camera_rival);
  }
  return poses;
}

}  // namespace

ProofVerdict judgeProof(const LineSetData& line_set, const PreparedMap& map,
                        const Eigen::Isometry3d& tracked, const Localization& found,
                        const AcquisitionOptions& acquisition, const PoseOffset& agreement) {
  const Alignment& alignment = found.alignment;
  const bool ambiguous = alignment.status == AlignmentStatus::kAmbiguous;
  if (alignment.status != AlignmentStatus::kOk && !ambiguous) {
    return {Proof::kUndecided, alignment.message + "; tried again later", {}, false};
  }
  const auto agrees = [&](const Eigen::Isometry3d& pose) {
    return PoseOffset::between(tracked, pose).within(agreement);
  };
  if (!ambiguous && agrees(alignment.T_world_camera.pose)) {
    return {Proof::kAgrees, "agrees with tracking", {}, true};
  }
  const double sky_clutter_density = found.search ? found.search->sky_clutter_density : 0.0;
  const auto score = [&](const Eigen::Isometry3d& T_world_camera) {
    return verificationScore(line_set.segments, map.segments, map.scene, T_world_camera,
                             line_set.camera, sky_clutter_density, acquisition);
  };
  const double tracked_score = score(tracked);
  const double fraction = acquisition.ambiguous_score_fraction;
  ProofVerdict verdict{Proof::kUndecided, ambiguous ? alignment.message + "; " : "", {}, true};
  for (const Eigen::Isometry3d& pose : foundPoses(found)) {
    if (agrees(pose)) {
      continue;
    }
    const double found_score = score(pose);
    const PoseOffset offset = PoseOffset::between(tracked, pose);
    verdict.outcome +=
        fmt::format("finds a pose {:.2f} m from tracking, which scores {:.1f} to its {:.1f}; ",
                    offset.position_m, tracked_score, found_score);
    if (!ambiguous && tracked_score < fraction * found_score) {
      verdict.proof = Proof::kContradicts;
      verdict.outcome += "tracking stops; the robot is searched for again";
      return verdict;
    }
    if (found_score >= fraction * tracked_score) {
      verdict.rival = verdict.rival.farthest(offset);
    }
  }
  if (verdict.rival.position_m > 0.0) {
    verdict.outcome += "its rival widens the fixes until tracking is proven; ";
  }
  verdict.outcome += "tried again later";
  return verdict;
}

TrackingProof::TrackingProof(const TrackingProofOptions& options, const LocalizerOptions& localizer)
    : options_(options), localizer_(localizer) {}

PoseOffset TrackingProof::agreement() const {
  return {options_.confirm_position_m, options_.confirm_rotation_rad};
}

void TrackingProof::startFromSearch(int64_t stamp_ns, const OdometryPose& odometry,
                                    const HypothesisDecision& decision) {
  const PoseWithCovariance& found = decision.hypothesis.T_world_camera;
  // A pose too wide to track from is tracked within the tracking limits; its
  // own width is then part of what the fixes leave unproven.
  PoseOffset unproven = decision.covered;
  if (needsAcquisition(found, localizer_)) {
    unproven = unproven.farthest(
        {largestPositionSigma(found.covariance), std::sqrt(std::max(0.0, found.covariance(5, 5)))});
  }
  start_ = Start{.origin = {stamp_ns, found, odometry}, .searched = true, .rival = unproven};
  searching_again_ = false;
}

std::optional<PoseWithCovariance> TrackingProof::carriedStart(int64_t stamp_ns,
                                                              const OdometryPose& odometry) const {
  if (!start_ || !start_->searched || start_->origin.odometry.epoch != odometry.epoch) {
    return std::nullopt;
  }
  const TrackingOrigin& origin = start_->origin;
  const double age_s = (stamp_ns - origin.stamp_ns) * 1e-9;
  if (!(age_s > 0.0 && age_s <= options_.carry_search_s)) {
    return std::nullopt;
  }
  // A O_A^-1 O.
  return narrowedForTracking(
      composeExactMotion(origin.T_world_camera_found, motionBetween(origin.odometry, odometry)),
      localizer_);
}

PoseWithCovariance TrackingProof::searchPrior(const PoseWithCovariance& prior) const {
  if (!searching_again_) {
    return prior;
  }
  PoseWithCovariance widened = prior;
  const double floor_variance = options_.proof_position_sigma_m * options_.proof_position_sigma_m;
  for (int axis = 0; axis < 2; ++axis) {
    widened.covariance(axis, axis) = std::max(widened.covariance(axis, axis), floor_variance);
  }
  return widened;
}

TrackingProof::Unproven TrackingProof::unprovenAt(int64_t stamp_ns, const OdometryPose& odometry,
                                                  const PoseWithCovariance& T_world_camera_fixed) {
  Unproven unproven;
  if (!start_ || start_->origin.odometry.epoch != odometry.epoch) {
    start_ = Start{.origin = {stamp_ns, T_world_camera_fixed, odometry}};
    unproven.started_from_prediction = true;
  }
  if (start_->agreeing_proofs >= options_.agreeing_proofs_needed) {
    return unproven;
  }
  const double moved_m = movedFrom(*start_, odometry);
  if (moved_m >= start_->proof_due_m) {
    unproven.proof_due = ProofRequest{start_->origin, moved_m};
  }
  const PoseOffset proof_reach{options_.proof_position_sigma_m, options_.confirm_rotation_rad};
  const PoseOffset rival =
      start_->looked_around ? start_->rival : start_->rival.farthest(proof_reach);
  const AcquisitionOptions& acquisition = localizer_.acquisition;
  unproven.offset = rival.farthest(
      {acquisition.acquired_position_sigma_m, acquisition.acquired_rotation_sigma_rad});
  return unproven;
}

bool TrackingProof::proven() const {
  return start_ && start_->agreeing_proofs >= options_.agreeing_proofs_needed;
}

double TrackingProof::movedFrom(const Start& start, const OdometryPose& odometry) {
  return (odometry.T_odom_camera.translation() - start.origin.odometry.T_odom_camera.translation())
      .norm();
}

bool TrackingProof::resume(const TrackingHandover& handover, int64_t stamp_ns,
                           const OdometryPose& odometry,
                           const PoseWithCovariance& T_world_camera_fixed,
                           const PoseWithCovariance& T_world_camera_predicted) {
  const Eigen::Matrix<double, 6, 6>& predicted = T_world_camera_predicted.covariance;
  const double max_position_variance = std::pow(options_.confirm_position_m / 3.0, 2);
  const double max_rotation_variance = std::pow(options_.confirm_rotation_rad / 3.0, 2);
  const bool narrow = predicted.diagonal().head<3>().maxCoeff() <= max_position_variance &&
                      predicted.diagonal().tail<3>().maxCoeff() <= max_rotation_variance;
  const bool started_here = start_ && start_->origin.odometry.epoch == odometry.epoch;
  if ((started_here && start_->agreeing_proofs >= handover.agreeing_proofs) || !handover.tracking ||
      handover.stamp_ns >= stamp_ns || !narrow ||
      !PoseOffset::between(T_world_camera_predicted.pose, T_world_camera_fixed.pose)
           .within(agreement())) {
    return false;
  }
  start_ = Start{.origin = {stamp_ns, T_world_camera_fixed, odometry},
                 .agreeing_proofs = handover.agreeing_proofs,
                 .proof_due_m = std::max(0.0, handover.proof_due_in_m),
                 .rival = handover.rival,
                 .looked_around = handover.looked_around};
  searching_again_ = false;
  return true;
}

TrackingHandover TrackingProof::handover(int64_t stamp_ns, const OdometryPose& odometry) const {
  if (!start_ || start_->origin.odometry.epoch != odometry.epoch) {
    return {.stamp_ns = stamp_ns};
  }
  return TrackingHandover{.stamp_ns = stamp_ns,
                          .tracking = true,
                          .agreeing_proofs = start_->agreeing_proofs,
                          .proof_due_in_m = start_->proof_due_m - movedFrom(*start_, odometry),
                          .rival = start_->rival,
                          .looked_around = start_->looked_around};
}

bool TrackingProof::apply(const ProofVerdict& verdict, const ProofRequest& request) {
  if (!start_ || !(start_->origin == request.origin)) {
    return false;
  }
  if (verdict.proof == Proof::kContradicts) {
    start_.reset();
    searching_again_ = true;
    return true;
  }
  const bool from_elsewhere = request.moved_m >= options_.acquisition_proven_after_m;
  start_->agreeing_proofs += verdict.proof == Proof::kAgrees && from_elsewhere ? 1 : 0;
  start_->rival = start_->rival.farthest(verdict.rival);
  start_->looked_around |= verdict.looked_around;
  start_->proof_due_m =
      std::max(request.moved_m + options_.proof_retry_m, options_.acquisition_proven_after_m);
  return true;
}

PoseWithCovariance TrackingProof::proofPrior(const Eigen::Isometry3d& tracked,
                                             double ground_sigma_m) const {
  PoseWithCovariance prior{tracked, diagonalPoseCovariance(options_.proof_position_sigma_m,
                                                           options_.confirm_rotation_rad)};
  prior.covariance(2, 2) = ground_sigma_m * ground_sigma_m;
  return prior;
}

}  // namespace lineloc
