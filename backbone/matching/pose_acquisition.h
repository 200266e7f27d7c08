// Finds the camera from a poor prior (paper §3.2: "a false match gives a
// precise but wrong pose"): the pose search (pose_search.h) proposes the best
// distinct poses over the prior's region; each one is aligned (gated matching
// and robust refinement, model_alignment.h) from its grid cell, with the lines
// visible from it. Each aligned pose is scored again by (C - K) / sqrt(L): its
// coverage C of L against a sharp distance map (a few pixels: aligned lines
// lie on their edges), less the length K of image edges in its open sky,
// weighed by how little the clutter of the frame's sky explains them
// (sky_edges.h). The best one wins — unless another one, distinct from it,
// scores nearly as well: then the view does not tell them apart (a
// repetitive street, a single façade) and the answer is kAmbiguous, never the
// likelier of two precise poses; nor is a best scoring under
// min_verification_score, too weak for that comparison to mean anything. An
// alignment that fits but is ill-conditioned (its covariance too wide to
// answer with) is such a rival too, though it never wins. Inlier counts do
// not separate them: a wrong pose near a façade full of windows finds as many
// lines to agree with.
//
// A hypothesis keeps the prior's height, which a ground robot knows to a
// decimetre; one whose alignment leaves it beyond height_gate_sigmas of that
// has matched the model at another height (window rows for a roof line) and
// competes no further.
//
// An acquired pose may still have settled on a neighbour of the right one a
// window's width away (a near-parallel line taken for the right one): its
// covariance, once widened for its inliers' redundancy (widenForConfidence,
// model_alignment.h), gets the search's own resolution, acquired_*_sigma,
// added, unscaled, so that the robot takes it as a start and tracking
// (tight gates, many frames) brings it to centimetres.
//
// Every pixel length in these options, and the scores, are in pixels of a
// camera of focal length reference_focal_px: each frame is seen through its
// reference view (reference_view.h), so that the same street seen by a
// 640 x 480 and a 5 megapixel camera is decided alike.
#pragma once

#include <limits>
#include <optional>
#include <vector>

#include "backbone/matching/model_alignment.h"
#include "backbone/matching/pose_search.h"
#include "backbone/matching/reference_view.h"
#include "backbone/matching/sky_edges.h"

namespace lineloc {

struct AcquisitionOptions {
  // The focal length (pixels) whose pixels the options below are given in:
  // the simulator's default camera, 62 degrees across 640 pixels.
  double reference_focal_px = 536.0;
  PoseSearchOptions search;
  // A hypothesis's alignment keeps a wide loss (model_alignment.h,
  // loss_scale_sigma): it starts up to the fine grid's reach from the truth,
  // and from a wrong hypothesis the narrow loss of tracking fits the lines
  // near it and ignores the rest. Nor does it leave out the matches on a
  // façade's side (facade_side_cut_sigma), which needs the pose within a
  // pixel or so.
  AlignmentOptions alignment = [] {
    AlignmentOptions wide_loss;
    wide_loss.loss_scale_sigma = 2.0;
    wide_loss.facade_side_cut_sigma = std::numeric_limits<double>::infinity();
    return wide_loss;
  }();
  // Covariance an alignment starts from at a hypothesis: the fine grid's reach.
  double hypothesis_position_sigma_m = 0.15;
  double hypothesis_rotation_sigma_rad = 0.2 * M_PI / 180.0;
  // Hidden-line removal for the alignment at each hypothesis.
  VisibilityOptions visibility;
  DistanceMapOptions verification_distances{15.0, 3.0, 1};
  // Added to an acquired pose's covariance (standard deviations); below the
  // localizer's tracking limits, so the next frame is tracked, unless the
  // alignment's own covariance takes the sum past them (a poor match; see
  // carried_start_step_m, line_set_handler.h).
  double acquired_position_sigma_m = 0.15;
  double acquired_rotation_sigma_rad = 0.3 * M_PI / 180.0;
  // The best aligned hypothesis needs this many inliers: a wrong pose near a
  // façade finds a handful of window lines to agree with, the right one most
  // of the building outlines in view. Hypotheses with fewer still compete (a
  // weak but better-scoring one is never passed over for a worse one).
  int min_inliers = 13;
  // A second aligned hypothesis scoring at least this fraction of the best
  // one, farther than distinct_position_m or distinct_yaw_rad from it, makes
  // the answer ambiguous.
  double ambiguous_score_fraction = 0.65;
  // The best aligned hypothesis must score at least this, whatever its
  // rivals score: below it the view holds too little evidence for the
  // fraction above to mean anything (a best of 2.6 against a rival of -13.8
  // passes it); the truth itself scores above it.
  double min_verification_score = 5.0;
  // An aligned hypothesis farther than this many of the prior's height
  // sigmas from its height is not the camera: the search keeps the prior's
  // height, which a ground robot knows from the model's ground level to a
  // decimetre (robot_session.h).
  double height_gate_sigmas = 3.0;
  // The weakest image segment a search takes (ImageSegment::contrast, the
  // mean grey-level step across it); tracking takes every one the robot sends.
  // The faint steps (about 12 grey levels and up, robot_agent.h) hold the
  // walls in shade that tracking down a narrow street needs, but also window
  // frames, shadows and cars that no model holds, which a search from afar
  // fits as readily as a building's outline.
  double min_segment_contrast = 20.0;
  SkyEdgeOptions sky_edges;
};

// Coverage of aligned poses against the sharp verification distance map of
// one frame's image, in its reference view: how acquisition scores its
// aligned hypotheses, and tracking its disagreeing alignments (localizer.h).
class CoverageVerifier {
 public:
  CoverageVerifier(const std::vector<ImageSegment>& image, const PinholeCamera& camera,
                   const AcquisitionOptions& options);
  // Of a frame already in its reference view.
  CoverageVerifier(const ReferenceView& view, const AcquisitionOptions& options);

  Coverage coverage(const std::vector<VisibleSegment>& visible,
                    const Eigen::Isometry3d& T_world_camera) const;

 private:
  PinholeCamera camera_;
  PoseSearchOptions options_;
  OrientedDistanceMap map_;
};

// One aligned hypothesis of a search: an alignment that settled on a pose
// (OK, or ill-conditioned), its own covariance unwidened, and its
// verification score (C - K) / sqrt(L).
struct ScoredHypothesis {
  PoseWithCovariance T_world_camera;
  AlignmentStatus status = AlignmentStatus::kOk;
  int inliers = 0;
  double score = 0.0;
  // The carried start it was aligned from (acquirePose), or -1 for the grid's.
  int carried_index = -1;
};

// What a search found, for logs, benchmarks and the evidence kept across
// frames (hypothesis_set.h).
struct SearchSummary {
  // Hypotheses the grid search proposed and how many of them aligned.
  int hypotheses = 0;
  int aligned = 0;
  // Verification scores (C - K) / sqrt(L) of the best aligned pose and its
  // best distinct rival (0: none).
  double best_score = 0.0;
  double rival_score = 0.0;
  // The rival's aligned pose, when there is one.
  std::optional<Eigen::Isometry3d> T_world_camera_rival;
  // Time of the grid search alone (pose_search.h).
  int64_t search_ns = 0;
  // Every aligned hypothesis, those from carried starts included.
  std::vector<ScoredHypothesis> aligned_hypotheses;
  // The frame's sky clutter density (1 / px, sky_edges.h): the least of its
  // aligned hypotheses' clear skies'.
  double sky_clutter_density = 0.0;
};

struct Acquisition {
  Alignment alignment;
  // The model pieces visible from the best aligned hypothesis.
  std::vector<VisibleSegment> visible;
  SearchSummary summary;
};

// `lines` and `scene` are the model near the prior; `prior.pose` carries the
// height the search keeps (see pose_search.h). Of `segments`, it takes those
// of at least min_segment_contrast. `carried_starts` are aligned and scored
// beside the grid's hypotheses: the poses earlier frames' searches found,
// moved to this frame (hypothesis_set.h), which the grid may not propose again.
Acquisition acquirePose(const std::vector<ImageSegment>& segments,
                        const std::vector<ModelSegment>& lines, const OcclusionScene& scene,
                        const PoseWithCovariance& prior, const PinholeCamera& camera,
                        const AcquisitionOptions& options,
                        const std::vector<Eigen::Isometry3d>& carried_starts = {});

// One hypothesis as acquirePose aligns and scores each of its starts, from
// `start`: for a caller that weighs a pose found in another frame in this one
// (hypothesis_set.h). nullopt when it settles on no pose.
// `sky_clutter_density` is the frame's (SearchSummary).
std::optional<ScoredHypothesis> alignHypothesis(
    const std::vector<ImageSegment>& segments, const std::vector<ModelSegment>& lines,
    const OcclusionScene& scene, const PoseWithCovariance& prior, const Eigen::Isometry3d& start,
    const PinholeCamera& camera, double sky_clutter_density, const AcquisitionOptions& options);

// The score (C - K) / sqrt(L) acquisition gives its aligned hypotheses, of a
// pose found otherwise (the tracked pose a proof search is checked against,
// line_set_handler.h), with the model visible from it as from a hypothesis,
// on the segments a search takes, its sky clutter density the search's of the
// frame (SearchSummary).
double verificationScore(const std::vector<ImageSegment>& segments,
                         const std::vector<ModelSegment>& lines, const OcclusionScene& scene,
                         const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera,
                         double sky_clutter_density, const AcquisitionOptions& options);

}  // namespace lineloc
