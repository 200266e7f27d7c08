// The planar start of Persa & Jonker §2.2: the pose from four or more coplanar
// model points through the plane-to-image homography, decomposed as in
// Ganapathy, "Decomposition of Transformation Matrices for Robot Vision"
// (Pattern Recognition Letters 2(6), 1984), and Zhang (ICCV 1999, eq. 5):
//
//   K^-1 H = lambda [r1 r2 t],   lambda = 2 / (|K^-1 h1| + |K^-1 h2|),
//   r3 = r1 x r2,   R = U V^T for [r1 r2 r3] = U S V^T (nearest rotation),
//
// the sign of lambda putting the model plane in front of the camera.
//
// A plane seen under perspective has a two-fold ambiguity (Schweighofer & Pinz,
// "Robust Pose Estimation from a Planar Target", PAMI 2006): a second pose,
// whose plane normal is the first one's mirrored about the line of sight to the
// plane's centroid, fits nearly as well when the plane is small or far. Both
// candidates are returned, with their residuals, for refinement to decide.
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "common/pose/pose_problem.h"

namespace lineloc {

// Coplanar when the smallest singular value of the centred model points is
// below this fraction of the largest (a start only: refinement uses the 3D points).
inline constexpr double kCoplanarTolerance = 1e-4;

// T_world_plane: origin at the centroid, z along the normal, when the model
// points are coplanar and not collinear; nullopt otherwise.
std::optional<Eigen::Isometry3d> fitModelPlane(const std::vector<PointCorrespondence>& points);

struct PlanarPoseCandidate {
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
  // RMS image distance of the points projected with this pose, in pixels.
  double rms_residual_px = 0.0;
};

struct PlanarPoseStart {
  // kConverged when candidates were found; kNotEnoughCorrespondences below
  // four points; kDegenerate for non-coplanar or collinear points or a
  // homography with no pose in it.
  PoseStatus status = PoseStatus::kNotEnoughCorrespondences;
  std::string message;
  // One or two candidates, smallest residual first.
  std::vector<PlanarPoseCandidate> candidates;
};

// Assumes checkPoseInput passed on the points.
PlanarPoseStart planarPose(const PinholeCamera& camera,
                           const std::vector<PointCorrespondence>& points);

}  // namespace lineloc
