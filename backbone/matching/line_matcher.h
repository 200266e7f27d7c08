// Candidate correspondences between the image segments a robot saw and the
// visible model segments, gated by the predicted pose's uncertainty (paper
// §3.2: the camera position is only approximately known).
//
// Each visible model segment is projected with the predicted pose; the
// covariance of a projected endpoint u = pi(R^T (P - t)) is J Sigma J^T with
// J = d pi / d p_c [-R^T, R^T [P - t]x] for the error e = [dp; dtheta] of
// common/geometry/pose.h (left perturbation: p_c ~ R^T (x + [x]x dtheta - dp),
// x = P - t). An image segment matches a model segment when the normal
// distances d_i of its endpoints to the projected model line pass the
// chi-square gate sum_i d_i^2 / (n^T (Sigma_image_i + Sigma_model) n) <= gate
// (two degrees of freedom), and it overlaps the projected segment along the
// line by at least a fraction of its own length. Where the model predicts which
// side of the line is brighter (VisibleSegment::polarity, visible_lines.h) and
// the image segment has a polarity, the two must agree, read along the same
// direction.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "backbone/visibility/visible_lines.h"
#include "common/camera/camera_calibration.h"
#include "common/geometry/pose.h"
#include "common/messages/messages.h"

namespace lineloc {

struct MatchingOptions {
  // chi^2 with 2 degrees of freedom: 13.82 keeps 99.9 % of true matches.
  double gate_chi2 = 13.82;
  double min_overlap_fraction = 0.3;
  // Floor on the model line's projected normal sigma (pixels): model lines are
  // not exact (generalised city models), and the floor keeps gates finite.
  double model_sigma_floor_px = 1.0;
  // Keep image segments off model lines of the other predicted polarity.
  bool use_polarity = true;
};

struct LineMatch {
  int image_index = 0;
  int model_index = 0;
  double chi2 = 0.0;
};

// A projected model point: its pixel and that pixel's 2x2 covariance under
// the pose covariance, J Sigma J^T.
struct ProjectedPoint {
  Eigen::Vector2d pixel;
  Eigen::Matrix2d covariance;
};

ProjectedPoint projectPoint(const Eigen::Vector3d& p_world,
                            const PoseWithCovariance& T_world_camera, const PinholeCamera& camera);

// Projected model segment with the pixel covariance of its endpoints.
struct ProjectedSegment {
  Eigen::Vector2d start_px;
  Eigen::Vector2d end_px;
  Eigen::Matrix2d start_covariance;
  Eigen::Matrix2d end_covariance;
};

ProjectedSegment projectSegment(const Eigen::Vector3d& start_world,
                                const Eigen::Vector3d& end_world,
                                const PoseWithCovariance& T_world_camera,
                                const PinholeCamera& camera);

// For each image segment, every model segment inside the gate, best first.
std::vector<std::vector<LineMatch>> gateCandidates(const std::vector<ImageSegment>& image,
                                                   const std::vector<VisibleSegment>& model,
                                                   const PoseWithCovariance& T_world_camera,
                                                   const PinholeCamera& camera,
                                                   const MatchingOptions& options);

}  // namespace lineloc
