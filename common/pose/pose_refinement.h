// Iterative refinement of a camera pose from point and line correspondences:
// Lowe's algorithm in the fully projective formulation of Araújo, Carceroni and
// Brown, "A Fully Projective Formulation to Improve the Accuracy of Lowe's
// Pose-Estimation Algorithm", CVIU 70(2), 1998 (Persa & Jonker §2.2): project
// the model with the current pose, check the stop conditions, build the error
// vector e and the Jacobian J, solve J delta = e, update rotation and translation.
//
// The Jacobian is the exact derivative of the perspective projection
// (Araújo §3) rather than Lowe's affine approximation: with p_c = R p_w + t,
// u = fx x/z + skew y/z + cx, v = fy y/z + cy and the update
// R <- Exp(dtheta) R, t <- Exp(dtheta) t + dt (a left perturbation of
// T_camera_world), d p_c = dt - [p_c]x dtheta.
//
// Residuals, each divided by its standard deviation:
//  - point: r = W (project(p_c) - m), W^T W = Sigma^-1 of the measured point;
//  - line: for both projected model endpoints q, the signed distance
//    d = n^T (q - a) to the measured line through a, b (unit normal n), over
//    sigma_d^2 = (1 - s)^2 n^T Sigma_a n + s^2 n^T Sigma_b n with
//    s = (q - a)^T (b - a) / |b - a|^2, the variance of the measured line's
//    offset at q (first-order propagation of the endpoint covariances).
// The cost is 1/2 sum_i rho(|r_i|^2) over correspondences, with rho the
// identity, Huber or Cauchy; Levenberg–Marquardt (Marquardt's diagonal scaling)
// damps the Gauss–Newton step on the sqrt(rho')-scaled system (Triggs et al.,
// "Bundle Adjustment — A Modern Synthesis", §4.3).
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "common/pose/pose_problem.h"

namespace lineloc {

enum class RobustLoss { kNone, kHuber, kCauchy };

struct RefinementOptions {
  RobustLoss loss = RobustLoss::kNone;
  // Scale c of the loss in units of standard deviations: Huber is quadratic up
  // to |r| = c; Cauchy is c^2 log(1 + |r|^2 / c^2).
  double loss_scale = 2.0;
  int max_iterations = 100;
  // Stop when an accepted step lowers the cost by less than this fraction.
  double function_tolerance = 1e-14;
  // Stop when |dt| <= tol (|t| + tol) and |dtheta| <= tol (radians).
  double parameter_tolerance = 1e-13;
  // Stop when a step is this small against the pose's own uncertainty:
  // dx^T (J^T W J) dx below it, dx^T I dx being the step's squared length in
  // standard deviations of the estimate (0: never; 1e-6 stops at a thousandth
  // of a standard deviation, where a flat robust cost can otherwise creep on
  // for many iterations).
  double step_information_tolerance = 0.0;
  // Stop when the largest entry of the gradient J^T r is below this.
  double gradient_tolerance = 1e-16;
  double initial_damping = 1e-4;
  // Damping beyond this means no step lowers the cost: at a minimum.
  double max_damping = 1e16;
  // kDegenerate when the smallest eigenvalue of the Jacobi-scaled information
  // matrix J^T J is below this fraction of the largest.
  double degeneracy_threshold = 1e-12;
  // kInconsistent when the correspondences' normalized residuals (|r_i|,
  // sqrt(2) expected for two unit-variance components) exceed this: their RMS
  // with RobustLoss::kNone, their median with a robust loss, which expects
  // outliers. The data then do not fit the stated noise (wrong matches, no
  // valid pose).
  double max_normalized_residual = 5.0;
};

// Refines from T_world_camera_start. Checks the input first (kInvalidInput,
// kNotEnoughCorrespondences, kDegenerate; kBehindCamera when the start sees no
// model feature in front of the camera, or the refined pose still sees one behind).
PoseEstimate refinePose(const PoseProblem& problem, const Eigen::Isometry3d& T_world_camera_start,
                        const RefinementOptions& options = {});

// The same without the input checks, for callers that ran checkPoseInput and
// checkPoseGeometry (common/pose/pose_input_check.h) on this problem.
PoseEstimate refineCheckedPose(const PoseProblem& problem,
                               const Eigen::Isometry3d& T_world_camera_start,
                               const RefinementOptions& options);

// Jackknife covariance of a refined pose (Efron & Stein, "The Jackknife
// Estimate of Variance", Ann. Statist. 9(3), 1981), for correspondences that
// may share one error: line correspondence i belongs to group line_groups[i]
// in [0, lines) (the image pieces of one model line, say; std::invalid_argument
// otherwise), each point is a group of its own,
// and each group g in turn is left out. With the robust weights w_i at the
// pose, the one-step shift of the solution without g is
//   dx_g = (H - H_g)^-1 sum_{i in g} w_i J_i^T r_i,  H_g = sum_{i in g} w_i J_i^T J_i,
// and the covariance (G - 1) / G sum_g (dx_g - mean)(dx_g - mean)^T over the G
// groups, in the pose.h convention. Unlike (J^T W J)^-1 it grows with what the
// residuals show rather than what the noise model promises: a few wrong
// matches pulling the pose make it wide. Infinite when leaving out one group
// leaves the pose undetermined.
Matrix6d leaveGroupOutCovariance(const PoseProblem& problem,
                                 const Eigen::Isometry3d& T_world_camera,
                                 const std::vector<int>& line_groups,
                                 const RefinementOptions& options);

}  // namespace lineloc
