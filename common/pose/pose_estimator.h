// Camera pose from point and line correspondences, the two steps of Persa &
// Jonker §2.2: a start pose — the prior when one is given, else Ganapathy's
// planar start through the homography (common/pose/planar_pose.h) when the
// model points are coplanar, else the linear start from points and lines
// (common/pose/linear_pose.h) — refined by Araújo's fully projective iteration
// (common/pose/pose_refinement.h).
//
// Both planar candidates are refined; when both converge to distinct poses
// whose chi^2 = sum of squared normalized residuals differ by less than
// ambiguity_chi2, the status is kAmbiguous. The other pose, when it
// converged, is always reported with its RMS residual.
#pragma once

#include <Eigen/Geometry>
#include <optional>

#include "common/pose/pose_problem.h"
#include "common/pose/pose_refinement.h"

namespace lineloc {

struct PoseOptions {
  RefinementOptions refinement;
  // Start from this pose instead of a closed-form start (e.g. the robot's
  // predicted pose); needed for fewer than six non-coplanar correspondences.
  std::optional<Eigen::Isometry3d> prior_T_world_camera;
  // kAmbiguous below this chi^2 difference between the two planar solutions
  // (4 = a two-sigma likelihood-ratio test on one parameter).
  double ambiguity_chi2 = 4.0;
};

PoseEstimate estimatePose(const PoseProblem& problem, const PoseOptions& options = {});

}  // namespace lineloc
