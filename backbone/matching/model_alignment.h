// Aligns the visible model with the image: the pose that makes the model's
// building lines fall on the segments the robot saw (paper §3.2), robust to
// the image lines of things not in the model (windows, cars, trees).
//
// Iterated gating: candidates are gated with the prior (line_matcher.h), each
// image segment keeps its best candidate, and the pose is refined on all of
// them with a Cauchy loss (common/pose) narrow enough that façade detail
// beside a building edge barely pulls (loss_scale_sigma). The refinement does
// not weigh the prior, so the two are taken as independent estimates: the
// next round gates with their fusion (fusePoses, common/geometry/pose.h) and
// refines from its centre, until the pose stops moving. Gating with the
// refined pose alone widened the gates wherever a round's matches left the
// pose undetermined: on a Delft frame predicted at the truth with nine model
// segments in view, the second round took in 22 candidates instead of 7 and
// the alignment settled 1.3 m off reporting 0.2 m (tests/integration/drive).
// An OK answer then takes one more round that leaves out the matches on their
// façade's side (facade_side_cut_sigma, leaveOutFacadeSideDetail).
// A model line may take several collinear image pieces; an image segment
// takes at most one model line.
//
// Each correspondence's endpoint covariance is the image fit's plus the edge
// and model error floors below, divided by the model line's visibility weight.
// When the inliers' residuals exceed that noise, the pose covariance is scaled
// by the a-posteriori variance factor s^2 = chi^2 / (2 n - 6) (Förstner &
// Wrobel, "Photogrammetric Computer Vision", 2016, §4.2.3), so a fix is never
// more confident than its own residuals allow.
//
// That covariance still treats every match as independent. A façade puts
// window edges a few pixels from a building edge, each within its noise, and
// several of them can pull the pose the same way; the pose then moves by
// several of its own standard deviations. The reported covariance is therefore
// the smallest one that covers, in every direction, both the propagated noise
// and the jackknife covariance over model edges (leaveGroupOutCovariance,
// common/pose/pose_refinement.h): how far the pose moves when each edge's
// matches are left out in turn. When leaving out one model line leaves the pose
// undetermined, the answer is ill-conditioned.
//
// The answer is only OK when enough matches carry it and the result is well
// conditioned: too few inliers, or a position standard deviation beyond
// max_position_sigma_m (a long façade seen alone constrains nothing along
// it), or a refinement failure, each has its own status, so the robot never
// receives a precise but wrong pose.
//
// An ill-conditioned alignment is not answered with its pose and wide
// covariance either, as a partial fix for the robot's filter to take the
// well-determined directions from (Zhang, Kaess & Singh, "On degeneracy of
// optimization-based state estimation problems", ICRA 2016): such frames
// rarely leave a single direction open, their errors hold for seconds
// inside their wide covariance, and fused at frame rate as independent they
// pull the robot's filter further off than dead reckoning drifts.
//
// Where the lines leave the pose open, completeWithCorners adds the model's
// corners, matched with the robot's as point correspondences (the projected
// vertex's pixel offset, two residuals), under the same loss and noise model
// as the lines.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "backbone/matching/corner_matcher.h"
#include "backbone/matching/line_matcher.h"
#include "common/pose/pose_refinement.h"

namespace lineloc {

enum class AlignmentStatus {
  kOk,
  kTooFewMatches,
  kIllConditioned,
  kAmbiguous,
  kFailed,
  // Aligned, but beyond chi^2_6(0.9973) of the pose it started from
  // (localizer.h): the image and the prediction disagree.
  kInconsistent,
};

const char* toString(AlignmentStatus status);

struct AlignmentOptions {
  MatchingOptions matching;
  CornerMatchingOptions corners;
  int max_rounds = 6;
  int min_inliers = 6;
  // An inlier's final normalized residual is below this (standard deviations).
  double inlier_threshold_sigma = 3.0;
  // Position standard deviation (largest principal axis) beyond which the
  // alignment is ill-conditioned. Down a narrow street whose façades' feet
  // are hidden by parked cars, the lines and the few corners the image shows
  // fix the position along it to 0.5-0.7 m, and every other direction well:
  // the robot's filter takes from such an answer the directions it fixes.
  double max_position_sigma_m = 0.75;
  // Each round's refinement stops when a step lowers the cost by less than
  // this fraction, or moves the pose by less than this relative amount: far
  // below the pose's standard deviation, far above rounding.
  double function_tolerance = 1e-10;
  double parameter_tolerance = 1e-9;
  // ... or its step is below a thousandth of the pose's standard deviation.
  double step_information_tolerance = 1e-6;
  // Pose change (m, rad) below which the rounds have converged.
  double converged_translation_m = 1e-4;
  double converged_rotation_rad = 1e-5;
  // Beyond the fit's own noise, a segment endpoint is uncertain by the edge
  // localisation bias (blur, sampling: edge_sigma_floor_px) and the model
  // line by its survey error (model_sigma_m, seen at depth z as f sigma / z
  // pixels): sigma^2 = floor^2 + (f sigma_model / z)^2 is added isotropically.
  double edge_sigma_floor_px = 0.3;
  double model_sigma_m = 0.03;
  // A ground line (a building's foot, where its wall meets the pavement) is
  // surveyed less well than its roof: city models take a building's base from
  // terrain points around it, and pavements, kerbs and slopes put the visible
  // foot decimetres off (a model's bases spread -0.1..0.45 m about its
  // median, 5-95 %).
  double ground_line_sigma_m = 0.15;
  // Scale c of the refinement's Cauchy loss c^2 log(1 + r^2 / c^2), in
  // standard deviations of the residual r. Window frames and doors put image
  // edges parallel to the building edges and 1.5-4 px beside them (a fifth to
  // a third of the vertical lines matched from the truth take one), with
  // residuals of 2-5 standard deviations: the influence r / (1 + r^2 / c^2)
  // at c = 0.7 lets such an edge pull a third as hard as an inlier at one,
  // where at c = 2 it pulls as hard, and along a street those few vertical
  // edges fix the position. The narrower basin needs a prior within a few
  // pixels; acquisition's hypotheses keep c = 2 (pose_acquisition.h).
  double loss_scale_sigma = 0.7;
  // Once the rounds have ended (the pose stopped moving, or max_rounds ran
  // out), an OK alignment takes one more that leaves out each match whose image
  // segment lies more than this many standard deviations from its model line
  // on the side of the line's own façade (VisibleSegment::facade_side). Window
  // frames and doors lie on that side of a building edge only, and a loss
  // symmetric about the line cannot tell them from the edge; beyond the façade
  // there is sky or a farther building, which put no detail at the line. In a
  // street both sides' façades lie outward in the image, so their detail holds
  // the pose ahead of the truth. Cut from afar, the true edges would go too:
  // the cut waits for the rounds to end. Leaving out matches on one side
  // biases the rest by phi(k) / Phi(k) standard deviations the other way (0.29
  // at k = 1) where the edges' own noise is that wide; at the truth most of
  // them lie well within it. Tracking cuts only the alignment it answers with
  // (localizer.h).
  double facade_side_cut_sigma = 1.0;
  // Image segments whose best candidate is not this much better (chi^2) than
  // the second, within the first round, are left out: ambiguous under the prior.
  double ambiguity_margin_chi2 = 2.0;
  // Parallel model lines closer than this are one edge to the camera (the two
  // creases of a footprint jog; a fifth of the Delft model's walls are under
  // 0.2 m wide): the jackknife leaves their matches out together.
  double coincident_edge_m = 0.25;
  // The probability at which an answered alignment's chi^2_6 region holds
  // (widenForConfidence); alignModel itself reports the unscaled covariance,
  // which every decision on alignments uses.
  double confidence = 0.9973;
};

struct Alignment {
  AlignmentStatus status = AlignmentStatus::kFailed;
  std::string message;
  PoseWithCovariance T_world_camera;
  int matches = 0;
  int inliers = 0;
  // The image corners (indices into the image's) among the inliers: the
  // corners a completion with corners used.
  std::vector<int> inlier_corners;
  double rms_residual_px = 0.0;
  int rounds = 0;
  // Where a further round would gate: the prediction fused with the last
  // round's pose, whose covariance the jackknife had not yet widened. The
  // façade-side cut's round gates there.
  PoseWithCovariance next_gate;
  // Time spent gating candidates, and estimating poses and their covariance.
  int64_t matching_ns = 0;
  int64_t pose_ns = 0;
};

// Rounds until the pose stops moving, then leaveOutFacadeSideDetail.
Alignment alignModel(const std::vector<ImageSegment>& image,
                     const std::vector<VisibleSegment>& model,
                     const PoseWithCovariance& predicted_T_world_camera,
                     const PinholeCamera& camera, const AlignmentOptions& options);

// What completeWithCorners matches: the robot's segments and corners
// (undistorted pixels) and the model's pieces and corners visible from the
// prediction. The caller keeps the four alive while it aligns.
struct AlignmentFeatures {
  const std::vector<ImageSegment>& image_segments;
  const std::vector<ImageCorner>& image_corners;
  const std::vector<VisibleSegment>& model_segments;
  const std::vector<VisibleCorner>& model_corners;
};

// An alignment the lines leave open (ill-conditioned, or too few matches)
// completed with the corners: the rounds again, with the model corners (visible_corners.h) matched
// with the image corners (corner_matcher.h) as point correspondences, the first gated at the lines'
// next_gate: as narrow as the lines' pose in every direction they determine, as wide as the
// prediction along those they leave open (the prediction itself when too few matched). Each matched
// corner is a jackknife group of its own (conclude), so one corner alone leaves the pose
// ill-conditioned: only two or more agreeing corners make it OK. The completed alignment is
// returned when OK, the lines' otherwise; any other alignment is returned as it is.
Alignment completeWithCorners(const Alignment& lines, const AlignmentFeatures& features,
                              const PoseWithCovariance& predicted_T_world_camera,
                              const PinholeCamera& camera, const AlignmentOptions& options);

// One more round for an OK alignment, gated at its next_gate, that leaves out
// the matches lying beyond facade_side_cut_sigma on their façade's side. The
// cut only sharpens an answer: when its round does not end OK (it left too few
// matches, or a pose the remaining edges do not determine), the alignment is
// kept as it was, with the round's time and count added. Any other alignment,
// or an infinite facade_side_cut_sigma, is returned as it is. A caller that
// aligns from several starts (localizer.h) aligns them with the cut off and
// cuts only the one it answers with.
Alignment leaveOutFacadeSideDetail(const Alignment& aligned, const std::vector<ImageSegment>& image,
                                   const std::vector<VisibleSegment>& model,
                                   const PinholeCamera& camera, const AlignmentOptions& options);

// An OK alignment's covariance, estimated from its own n inliers, scaled by
// confidenceScale(2 n - 6, confidence) (common/stats/confidence_scale.h) so
// that its chi^2_6(confidence) region holds the pose with that probability:
// 1.45 for 14 inliers, 1.8 for 10 at 0.9973. Other statuses are left alone.
void widenForConfidence(Alignment& alignment, double confidence);

}  // namespace lineloc
