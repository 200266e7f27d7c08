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
// optimization-based state estimation problems", ICRA 2016). Tried on the
// README's two-minute demo: 299 of its 367 ill-conditioned frames (6-12
// inliers, down a street past parked cars) had a finite covariance with a
// largest position sigma under 5 m, but only 10 left a single direction open
// (the others also 0.2-1.6 m across the street and 0.5-14 degrees in yaw).
// Their errors held for seconds (0.23 m across the street, inside a 0.42 m
// sigma, for two seconds); fused at 30 Hz as the robot fuses fixes, they left
// it 5.7-8.7 cm RMS off over 35-50 s, where dead reckoning alone gave
// 2.5-3.9 cm, and three were beyond three sigma.
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
  // alignment is ill-conditioned. Down a narrow street of LoD1 boxes, its
  // façades' feet hidden by parked cars, the lines and the few corners the
  // image shows fix the position along it to 0.5-0.7 m, and every other
  // direction well. On the README's two-minute drive answering them (0.5 m
  // before) took the answers OK from the first fix from 98.7 % to 99.6 %, the
  // position RMSE from 2.3 to 2.4 cm, with no fix and no robot state beyond
  // three sigma: the robot's filter takes from each the directions it fixes.
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
  // foot decimetres off. The simulated Delft drives render a flat ground at the
  // model's median base, about which the bases spread -0.1..0.45 m (5-95 %):
  // aligned from the truth, seed 1's ground lines lay 1.4 px off on average and
  // held its poses 0.8 cm low (0.05 cm with this sigma).
  double ground_line_sigma_m = 0.15;
  // Scale c of the refinement's Cauchy loss c^2 log(1 + r^2 / c^2), in
  // standard deviations of the residual r. Window frames and doors put image
  // edges parallel to the building edges and 1.5-4 px beside them. Of the
  // vertical model lines matched from the truth on simulated Delft frames,
  // 18-31 % took such an edge, half or more with no image edge at the model
  // line itself (a corner the image does not show). Their residuals are 2-5
  // standard deviations (medians 2.8-4.7 on three drives), where with c = 2
  // each pulled about as hard as an inlier at one (the influence is
  // r / (1 + r^2 / c^2)); with c = 0.7 it pulls a third as hard. Along a
  // street only the vertical edges fix the position, and a few of them held
  // the fixes of every drive 2-6 cm along it. With c = 0.7 and the ground
  // lines' sigma above, the position RMSE of 50 simulated drives fell from a
  // median of 4.1 cm (over 5 cm on 18) to 2.8 cm (over 5 cm on 8), with no
  // fix beyond three sigma; with the ground lines at model_sigma_m, seed 9
  // tracked its start's neighbouring basin, 0.6 m RMS off with 55 fixes
  // beyond three sigma (10 drives). The narrower basin needs a prior within a
  // few pixels: from 0.3 m off on the synthetic street of the unit tests,
  // detail 1-2 px beside the edges left some alignments unconverged;
  // acquisition's hypotheses keep c = 2 (pose_acquisition.h).
  //
  // What c = 0.7 leaves. Aligned frame by frame from the truth (a 5 cm, 0.2
  // degree prior) on every fourth driving frame of simulated Delft seeds 19, 11,
  // 23 and 47, the poses sat 5.2, 5.7, 5.2 and 4.1 cm ahead along the view on
  // average, as those drives' online fixes did (6.2, 5.7, 5.6, 3.4): the bias is
  // the views', not the filter's or the fixes' timing, and a pinhole render of
  // seed 19 keeps it (4.8 cm), so not the lens either. Against the truth, about a
  // quarter of its vertical lines' matches lay 0.5-1.5 px beside them, on the
  // façade's side: outward from the image centre on both sides of the street,
  // which a camera nearer the façades explains; the rest lay 0.02 px off on
  // average. The simulator's windows sit on a grid that ignores where walls end,
  // so a corner often cuts a window or lies beside its frame. Rendered without
  // windows (pinhole), seed 19's frames sat 0.7 cm ahead, but only 52 of 107
  // aligned, on 8-13 inliers (median 9; the rest ill-conditioned or short of
  // matches), where with windows 101 aligned, on 10-18 (median 12), a quarter of
  // the vertical ones such edges. Leaving out the vertical matches more than one
  // standard deviation outward took seed 19's bias from 5.2 to 3.4 cm (4.8 cm
  // beyond two), so those edges are not all of it. Windows kept 0.5 m in from
  // every wall's end (pinhole) took the edges beside corners away, but made a
  // basin of their own: 35 of 83 aligned frames settled 0.3-0.7 m off, most of
  // them ahead, each corner on the window column beside it.
  double loss_scale_sigma = 0.7;
  // Once the rounds have ended (the pose stopped moving, or max_rounds ran
  // out), an OK alignment takes one more that leaves out each match whose image
  // segment lies more than this many standard deviations from its model line
  // on the side of the line's own façade (VisibleSegment::facade_side). Window
  // frames and doors lie on that side of a building edge only, and a loss
  // symmetric about the line cannot tell them from the edge; beyond the façade
  // there is sky or a farther building, which put no detail at the line. In a
  // street both sides' façades lie outward in the image, so their detail held
  // the pose ahead of the truth (above). Cut from afar, the true edges would
  // go too: the cut waits for the rounds to end. Leaving out matches on one side
  // biases the rest by phi(k) / Phi(k) standard deviations the other way (0.29
  // at k = 1) where the edges' own noise is that wide; at the truth most of
  // them lie well within it. Over 49 simulated Delft drives (seeds 1-50; 41's
  // robot never started), with rounds until the pose stopped moving again, the
  // median position RMSE went from 2.37 to 2.17 cm and the drives over 5 cm
  // from 10 to 5, with no fix beyond three sigma; the mean error along the
  // view of seed 19's driving fixes from 6.3 to 3.0 cm, seed 11's from 6.0 to
  // 2.7. One round did as well on six of them, and costs less: a tracking frame
  // on one core took 5.9 ms without the cut, 7.8 ms with one round in the
  // alignment from every start and 8.9 ms with rounds to convergence (medians,
  // bench_localization_stages). Tracking cuts only the alignment it answers
  // with (localizer.h).
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
