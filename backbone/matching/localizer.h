// One frame's pose from the model near the prior — the step the backbone
// service and the offline tracker share. A prior tight enough for gated
// matching (largest position sigma and yaw sigma under the tracking limits:
// the robot's prediction between fixes) is tracked: hidden-line removal from
// the prior (visible_lines.h) and alignment (model_alignment.h). A poorer one
// (a DGPS + compass start, a long outage) is acquired: searched, aligned and
// verified (pose_acquisition.h).
//
// Tracking first trusts the prediction's centre: it aligns with the prior's
// covariance scaled by first_gate_scale^2, so the first round gates each model
// line within a few pixels of where the prediction puts it, and falls back to
// the whole covariance only when that alignment is not OK. The prediction
// after a fix carries the fix's covariance, which the jackknife makes
// conservative (model_alignment.h); gates that wide hold two model lines for
// many true building edges, which the alignment then leaves out as ambiguous,
// while the window frames beside the edges, each near one model line only,
// stay in and pull the pose.
//
// One start is not enough when the prediction's centre is itself off by a
// standard deviation (the first frames after a search, whose pose is only as
// good as its grid): the alignment settles in whichever basin holds the
// centre, and a view whose lines fit two depths a few decimetres apart gives a
// precise answer in the wrong one, which every later fix of a standstill
// keeps. Tracking therefore also aligns from sigma points of the prediction,
// its centre moved by +-start_sigma standard deviations along each principal
// axis of the position covariance and about the vertical. When an alignment
// that settled (OK, or ill-conditioned: it fits the image but leaves the pose
// too wide to answer with) lies outside
// the first OK one's covariance (beyond chi^2_6(0.9973)), each is scored by
// coverage against a sharp distance map, as acquisition verifies its
// hypotheses (pose_acquisition.h); the best OK one is answered, its covariance
// grown by d d^T for every rival covered nearly as well (d the rival's
// offset), so the answer covers the poses the view does not rule out, and the
// answer is ambiguous when that leaves it too wide to use. Along the
// horizontal axes the sigma points lie at least min_start_step_m from the
// centre, with the covariance along the axis widened to reach them: a
// prediction can be more confident than its error allows (the robot fuses
// fixes whose errors are correlated). 0.15 m is the reach of the search's
// fine grid, whose neighbouring basins an acquired pose can carry into the
// fixes after it. The height is not floored: a ground robot's camera rides at
// a known height, and probing up and down lets rivals of a few centimetres
// widen the answers.
//
// A sigma point probes the basins near the prediction; it cannot make a view
// determine the pose. When the centre's own alignment is ill-conditioned, that
// is the answer: from some sigma point a different subset of the same few
// matches can squeeze under max_position_sigma_m. And an OK alignment counts
// only within chi^2_6(0.9973) of its start in the sum of their covariances,
// the innovation gate of a Kalman update: in a view with few model lines a
// widened point's gates can take it a metre along the view. When the
// centre's alignment is out of its reach and no sigma point's is within, the
// answer is kInconsistent.
//
// Where the lines leave the pose open (the centre's alignment ill-conditioned,
// or too few matched, and no start's OK), the model's corners complete the
// centre's alignment (completeWithCorners, model_alignment.h), and the
// completion is the answer when it is OK and within the prior's reach. Corners
// serve nowhere else: many of the corners an image shows are window corners
// standing in for building vertices it does not show, which pull every
// alignment they join, so they only complete what the lines leave open.
//
// The starts align without the façade-side cut (model_alignment.h), and only
// the OK alignment answered takes its round, before its rivals widen it: a
// round in every start's alignment would cost a third more per frame for an
// answer that uses one of them.
//
// Every decision above uses the alignments' own covariances. The answer is
// then widened for how few matches estimated it (widenForConfidence,
// model_alignment.h: scaled by confidenceScale(2 n - 6, confidence) for its n
// inliers; 1.45 for 14 inliers, 1.8 for 10): answers from few matches are
// the ones beyond their unscaled covariance.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "backbone/matching/pose_acquisition.h"

namespace lineloc {

struct LocalizerOptions {
  double max_tracking_position_sigma_m = 0.2;
  double max_tracking_yaw_sigma_rad = 0.5 * M_PI / 180.0;
  // Scale of the prior's standard deviations for tracking's first alignment.
  double first_gate_scale = 0.1;
  // Tracking's sigma points, in the prior's standard deviations.
  double start_sigma = 1.5;
  // ... and at least this far along the horizontal axes, with the prior's
  // sigma along the axis widened to step / start_sigma.
  double min_start_step_m = 0.15;
  // A rival covered at least this fraction as well as the best tracked
  // alignment widens the answer's covariance to reach it.
  double rival_score_fraction = 0.8;
  // chi^2_6(0.9973): an alignment further from the answer in the answer's
  // covariance is outside it; an alignment further from its start, in the
  // sum of their covariances, is out of its reach.
  double distinct_chi2 = 20.06;
  // Threads sharing tracking's alignments from the prior and its sigma points,
  // and its hidden-line removal's lines (0: one per core).
  int threads = 0;
  // Tracking's hidden-line removal. Its sunlight, when set, is tracking's
  // alone: the acquisition's search and hypotheses keep the corners between
  // walls lit alike, whose true inliers its inlier rule needs.
  VisibilityOptions visibility;
  // Tracking's model corners, from its visible pieces (visible_corners.h).
  CornerOptions corners;
  AlignmentOptions alignment;
  AcquisitionOptions acquisition;
};

struct Localization {
  // Its matching_ns and pose_ns are the wall time of every alignment tried,
  // shared between the two as their time summed over the threads is; scoring
  // tracked alignments by coverage counts as matching.
  Alignment alignment;
  // Set when the pose was acquired by a search rather than tracked.
  std::optional<SearchSummary> search;
  // The model pieces visible from the prior (tracking) or from the winning
  // hypothesis (acquisition).
  std::vector<VisibleSegment> visible;
  int64_t visibility_ns = 0;
};

// True when `prior` is too poor for gated matching.
bool needsAcquisition(const PoseWithCovariance& prior, const LocalizerOptions& options);

// `prior` with its covariance scaled down, as a whole, until it meets the
// tracking limits: the gates to track a pose that other evidence has taken
// (hypothesis_set.h) although its own alignment left it wider.
PoseWithCovariance narrowedForTracking(const PoseWithCovariance& prior,
                                       const LocalizerOptions& options);

// Tracking's hidden-line removal from `prior` (visible_lines.h, under
// options.visibility on options.threads): the first step of localize for a
// prior needsAcquisition refuses, and the only one that needs no image, so a
// caller that knows the prior before the image's lines can run it meanwhile.
std::vector<VisibleSegment> visibleFromPrior(const std::vector<ModelSegment>& lines,
                                             const OcclusionScene& scene,
                                             const PoseWithCovariance& prior,
                                             const PinholeCamera& camera,
                                             const LocalizerOptions& options);

// `visible_from_prior`, when given, is visibleFromPrior's answer for these
// lines, scene, prior, camera and options, which tracking then takes instead
// of removing the hidden lines itself; a search ignores it.
Localization localize(const std::vector<ImageSegment>& image_segments,
                      const std::vector<ImageCorner>& image_corners,
                      const std::vector<ModelSegment>& lines, const OcclusionScene& scene,
                      const PoseWithCovariance& prior, const PinholeCamera& camera,
                      const LocalizerOptions& options,
                      const std::vector<VisibleSegment>* visible_from_prior = nullptr);

}  // namespace lineloc
