// A closed-form start for non-planar configurations: the direct linear
// transform of a calibrated camera from points and lines together (Hartley &
// Zisserman, "Multiple View Geometry", 2nd ed., §7.1 and §8.2.1; the line form
// as in Přibyl, Zemčík and Čadík, "Camera pose estimation from lines: a fast,
// robust and general method", MVA 2017).
//
// In normalized coordinates x = K^-1 [u v 1]^T, P = [R | t] up to scale:
//   point X <-> x:        x P3 X - P1 X = 0,   y P3 X - P2 X = 0
//   line  A B <-> l:      l^T P A = 0,         l^T P B = 0,  l = K^T (a x b)
// Every correspondence gives two equations on the 12 entries of P, so six are
// needed. The model is first moved to its centroid and scaled to unit RMS
// distance (Hartley's normalization); P is the eigenvector of A^T A with the
// smallest eigenvalue, signed so that most model points are in front of the
// camera, its left 3x3 block is
// projected onto SO(3) (common/pose/nearest_rotation.h), and t is divided by the scale |P_3x3|_F /
// sqrt(3).
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "common/pose/pose_problem.h"

namespace lineloc {

// status is kConverged when a start pose was found.
struct PoseStart {
  PoseStatus status = PoseStatus::kNotEnoughCorrespondences;
  std::string message;
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
};

// kNotEnoughCorrespondences below six correspondences; kDegenerate when the
// model points and endpoints are coplanar (use the planar start) or the system
// has more than one null direction. Assumes checkPoseInput passed.
PoseStart linearPose(const PoseProblem& problem);

}  // namespace lineloc
