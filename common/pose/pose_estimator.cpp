#include "common/pose/pose_estimator.h"

#include <fmt/format.h>

#include <vector>

#include "common/pose/linear_pose.h"
#include "common/pose/planar_pose.h"
#include "common/pose/pose_input_check.h"

namespace lineloc {

namespace {

// Two refined poses closer than this (radians, metres) are the same solution.
constexpr double kSameRotationRad = 1e-6;
constexpr double kSameTranslationM = 1e-6;

bool areSamePose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::AngleAxisd difference(a.linear().transpose() * b.linear());
  return difference.angle() < kSameRotationRad &&
         (a.translation() - b.translation()).norm() <
             kSameTranslationM * (1.0 + a.translation().norm());
}

// Refines every planar candidate and keeps the lowest-cost converged one,
// marking it ambiguous when the other is distinct and nearly as good.
PoseEstimate refinePlanarCandidates(const PoseProblem& problem, const PlanarPoseStart& start,
                                    const PoseOptions& options) {
  std::vector<PoseEstimate> refined;
  for (const auto& candidate : start.candidates) {
    refined.push_back(refineCheckedPose(problem, candidate.T_world_camera, options.refinement));
  }
  if (refined.size() == 1) {
    return refined.front();
  }
  if (refined[1].ok() && (!refined[0].ok() || refined[1].cost < refined[0].cost)) {
    std::swap(refined[0], refined[1]);
  }
  PoseEstimate& best = refined[0];
  const PoseEstimate& other = refined[1];
  if (!best.ok() || !other.ok() ||
      areSamePose(best.T_world_camera.pose, other.T_world_camera.pose)) {
    return best;
  }
  best.alternative_T_world_camera = other.T_world_camera.pose;
  best.alternative_rms_residual_px = other.rms_residual_px;
  const double chi2_difference = 2.0 * (other.cost - best.cost);
  if (chi2_difference < options.ambiguity_chi2) {
    best.status = PoseStatus::kAmbiguous;
    best.message =
        fmt::format("planar ambiguity: the mirrored pose's chi^2 is only {} higher (threshold {})",
                    chi2_difference, options.ambiguity_chi2);
  }
  return best;
}

}  // namespace

PoseEstimate estimatePose(const PoseProblem& problem, const PoseOptions& options) {
  if (auto invalid = checkPoseInput(problem)) {
    return poseFailure(invalid->status, invalid->message);
  }
  if (auto degenerate = checkPoseGeometry(problem)) {
    return poseFailure(degenerate->status, degenerate->message);
  }
  if (options.prior_T_world_camera) {
    return refineCheckedPose(problem, *options.prior_T_world_camera, options.refinement);
  }
  if (problem.points.size() >= 4 && fitModelPlane(problem.points)) {
    const PlanarPoseStart start = planarPose(problem.camera, problem.points);
    if (start.status != PoseStatus::kConverged) {
      return poseFailure(start.status, start.message);
    }
    return refinePlanarCandidates(problem, start, options);
  }
  const PoseStart start = linearPose(problem);
  if (start.status == PoseStatus::kConverged) {
    return refineCheckedPose(problem, start.T_world_camera, options.refinement);
  }
  if (start.status == PoseStatus::kNotEnoughCorrespondences) {
    return poseFailure(
        start.status,
        start.message + "; give a prior pose, 4 coplanar points or 6 non-coplanar features");
  }
  return poseFailure(start.status, start.message + "; give a prior pose or 4 coplanar points");
}

}  // namespace lineloc
