#include "backbone/matching/pose_acquisition.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "common/parallel/parallel_for.h"
#include "common/time/clock.h"

namespace lineloc {
namespace {

bool distinct(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
              const PoseSearchOptions& options) {
  const Eigen::AngleAxisd rotation(a.linear().transpose() * b.linear());
  return (a.translation() - b.translation()).head<2>().norm() >= options.distinct_position_m ||
         std::abs(rotation.angle()) >= options.distinct_yaw_rad;
}

struct Verified {
  // The carried start it was aligned from, or -1 for the grid's.
  int carried_index = -1;
  Alignment alignment;
  std::vector<VisibleSegment> visible;
  // Of the aligned pose: its coverage C of L against the verification
  // distance map, the edges in its open sky and its clear sky's area, and
  // the score (C - K) / sqrt(L) with K the sky's edge length weighed by the
  // evidence its edges carry.
  Coverage coverage;
  SkyEdges sky;
  double clear_sky_area_px2 = 0.0;
  double score = 0.0;
};

// (C - K) / sqrt(L); 0 where the coverage scores nothing (too little model in view).
double verifiedScore(const Coverage& coverage, const SkyEdges& sky, double sky_clutter_density,
                     const SkyEdgeOptions& options) {
  if (coverage.score <= 0.0) {
    return 0.0;
  }
  return (coverage.covered_px - weighedSkyEdgeLength(sky, sky_clutter_density, options)) /
         std::sqrt(coverage.model_px);
}

// The frame's sky clutter density: the least of its poses' clear skies'
// (sky_edges.h), 0 when none shows enough clear sky to measure it.
double skyClutterDensity(const std::vector<Verified>& aligned, const SkyEdgeOptions& options) {
  std::optional<double> least;
  for (const Verified& candidate : aligned) {
    const std::optional<double> density =
        clearSkyEdgeDensity(candidate.sky, candidate.clear_sky_area_px2, options);
    if (density && (!least || *density < *least)) {
      least = density;
    }
  }
  return least.value_or(0.0);
}

PoseWithCovariance hypothesisStart(const Eigen::Isometry3d& T_world_camera,
                                   const AcquisitionOptions& options) {
  return {T_world_camera, diagonalPoseCovariance(options.hypothesis_position_sigma_m,
                                                 options.hypothesis_rotation_sigma_rad)};
}

// The reference view of the image segments a search takes
// (AcquisitionOptions::min_segment_contrast).
ReferenceView searchedView(const std::vector<ImageSegment>& segments, const PinholeCamera& camera,
                           const AcquisitionOptions& options) {
  std::vector<ImageSegment> searched;
  std::copy_if(segments.begin(), segments.end(), std::back_inserter(searched),
               [&](const ImageSegment& segment) {
                 return segment.contrast >= options.min_segment_contrast;
               });
  return referenceView(searched, camera, options.reference_focal_px);
}

bool byScore(const Verified& a, const Verified& b) {
  return a.score < b.score;
}

// An alignment that settled on a pose: OK, or ill-conditioned (it fits the
// image but its covariance is too wide to answer with). Both compete as
// rivals; only an OK one can win.
bool hasPose(const Alignment& alignment) {
  return alignment.status == AlignmentStatus::kOk ||
         alignment.status == AlignmentStatus::kIllConditioned;
}

bool isOk(const Verified& candidate) {
  return candidate.alignment.status == AlignmentStatus::kOk;
}

// OK alignments above the others, then by score.
bool byOkThenScore(const Verified& a, const Verified& b) {
  if (isOk(a) != isOk(b)) {
    return isOk(b);
  }
  return byScore(a, b);
}

// Marks an aligned pose kInconsistent when its height lies beyond
// height_gate_sigmas of the prior's height sigma from the prior's.
void rejectOffTheHeight(const PoseWithCovariance& prior, const AcquisitionOptions& options,
                        Alignment& alignment) {
  const double height_offset_m =
      alignment.T_world_camera.pose.translation().z() - prior.pose.translation().z();
  const double gate_m = options.height_gate_sigmas * std::sqrt(prior.covariance(2, 2));
  if (!hasPose(alignment) || std::abs(height_offset_m) <= gate_m) {
    return;
  }
  alignment.status = AlignmentStatus::kInconsistent;
  alignment.message = fmt::format("aligned {:.2f} m from the prior's height, beyond {:.2f} m",
                                  height_offset_m, gate_m);
}

// The best-scoring aligned alternative that is distinct from `best`.
const Verified* bestRival(const std::vector<Verified>& aligned, const Verified& best,
                          const PoseSearchOptions& options) {
  const Verified* rival = nullptr;
  for (const Verified& other : aligned) {
    if (&other == &best || !distinct(other.alignment.T_world_camera.pose,
                                     best.alignment.T_world_camera.pose, options)) {
      continue;
    }
    if (rival == nullptr || byScore(*rival, other)) {
      rival = &other;
    }
  }
  return rival;
}

// A hypothesis aligned from `start` and scored (pose_acquisition.h).
Verified alignFrom(const std::vector<ImageSegment>& image, const CoverageVerifier& verifier,
                   const std::vector<ModelSegment>& lines, const OcclusionScene& scene,
                   const PoseWithCovariance& prior, const Eigen::Isometry3d& start_pose,
                   const PinholeCamera& camera, const AcquisitionOptions& options) {
  const PoseWithCovariance start = hypothesisStart(start_pose, options);
  Verified candidate;
  candidate.visible = visibleSegments(lines, scene, start, camera, options.visibility);
  candidate.alignment = alignModel(image, candidate.visible, start, camera, options.alignment);
  rejectOffTheHeight(prior, options, candidate.alignment);
  if (hasPose(candidate.alignment)) {
    const Eigen::Isometry3d& T_world_camera = candidate.alignment.T_world_camera.pose;
    candidate.coverage = verifier.coverage(candidate.visible, T_world_camera);
    candidate.sky = measureSkyEdges(image, T_world_camera, camera, scene, options.sky_edges);
  }
  return candidate;
}

// An aligned candidate as the search answers it: its covariance widened for
// its inliers' redundancy, with the search's resolution added.
ScoredHypothesis scored(const Verified& candidate, const AcquisitionOptions& options) {
  Alignment alignment = candidate.alignment;
  widenForConfidence(alignment, options.alignment.confidence);
  alignment.T_world_camera.covariance += diagonalPoseCovariance(
      options.acquired_position_sigma_m, options.acquired_rotation_sigma_rad);
  return {alignment.T_world_camera, alignment.status, alignment.inliers, candidate.score,
          candidate.carried_index};
}

}  // namespace

CoverageVerifier::CoverageVerifier(const std::vector<ImageSegment>& image,
                                   const PinholeCamera& camera, const AcquisitionOptions& options)
    : CoverageVerifier(referenceView(image, camera, options.reference_focal_px), options) {}

CoverageVerifier::CoverageVerifier(const ReferenceView& view, const AcquisitionOptions& options)
    : camera_(view.camera),
      options_(options.search),
      map_(view.segments, view.camera.width, view.camera.height, options.verification_distances) {}

Coverage CoverageVerifier::coverage(const std::vector<VisibleSegment>& visible,
                                    const Eigen::Isometry3d& T_world_camera) const {
  return measureCoverage(visible, T_world_camera, camera_, map_, options_);
}

Acquisition acquirePose(const std::vector<ImageSegment>& segments,
                        const std::vector<ModelSegment>& lines, const OcclusionScene& scene,
                        const PoseWithCovariance& prior, const PinholeCamera& camera,
                        const AcquisitionOptions& options,
                        const std::vector<Eigen::Isometry3d>& carried_starts) {
  const ReferenceView view = searchedView(segments, camera, options);
  Acquisition acquisition;
  acquisition.alignment.T_world_camera = prior;
  const int64_t search_start_ns = steadyClockNs();
  const PoseSearch search(lines, scene, view.camera, options.search);
  std::vector<Eigen::Isometry3d> starts;
  for (const PoseHypothesis& hypothesis : search.search(view.segments, prior)) {
    starts.push_back(hypothesis.T_world_camera);
  }
  acquisition.summary.search_ns = steadyClockNs() - search_start_ns;
  acquisition.summary.hypotheses = static_cast<int>(starts.size());
  const size_t grid_starts = starts.size();
  starts.insert(starts.end(), carried_starts.begin(), carried_starts.end());

  const CoverageVerifier verifier(view, options);
  std::vector<Verified> verified(starts.size());
  parallelFor(static_cast<int>(starts.size()), options.search.threads, [&](int i) {
    verified[i] =
        alignFrom(view.segments, verifier, lines, scene, prior, starts[i], view.camera, options);
    if (hasPose(verified[i].alignment)) {
      verified[i].clear_sky_area_px2 = clearSkyArea(verified[i].alignment.T_world_camera.pose,
                                                    view.camera, scene, options.sky_edges);
    }
    verified[i].carried_index =
        i < static_cast<int>(grid_starts) ? -1 : i - static_cast<int>(grid_starts);
  });
  std::vector<Verified> aligned;
  for (Verified& candidate : verified) {
    acquisition.alignment.matching_ns += candidate.alignment.matching_ns;
    acquisition.alignment.pose_ns += candidate.alignment.pose_ns;
    if (hasPose(candidate.alignment)) {
      aligned.push_back(std::move(candidate));
    }
  }
  acquisition.summary.sky_clutter_density = skyClutterDensity(aligned, options.sky_edges);
  for (Verified& candidate : aligned) {
    candidate.score = verifiedScore(candidate.coverage, candidate.sky,
                                    acquisition.summary.sky_clutter_density, options.sky_edges);
    acquisition.summary.aligned_hypotheses.push_back(scored(candidate, options));
  }
  acquisition.summary.aligned = static_cast<int>(aligned.size());
  const auto best = std::max_element(aligned.begin(), aligned.end(), byOkThenScore);
  if (best == aligned.end() || !isOk(*best)) {
    acquisition.alignment.status = AlignmentStatus::kTooFewMatches;
    acquisition.alignment.message = fmt::format(
        "none of {} search hypotheses aligned to a well-conditioned pose", starts.size());
    return acquisition;
  }
  const Verified* rival = bestRival(aligned, *best, options.search);
  const int64_t matching_ns = acquisition.alignment.matching_ns;
  const int64_t pose_ns = acquisition.alignment.pose_ns;
  acquisition.alignment = best->alignment;
  acquisition.alignment.T_world_camera = scored(*best, options).T_world_camera;
  acquisition.alignment.rms_residual_px /= view.scale;
  acquisition.visible = best->visible;
  acquisition.alignment.matching_ns = matching_ns;
  acquisition.alignment.pose_ns = pose_ns;
  acquisition.summary.best_score = best->score;
  if (rival != nullptr) {
    acquisition.summary.rival_score = rival->score;
    acquisition.summary.T_world_camera_rival = rival->alignment.T_world_camera.pose;
  }
  if (acquisition.alignment.inliers < options.min_inliers) {
    acquisition.alignment.status = AlignmentStatus::kTooFewMatches;
    acquisition.alignment.message =
        fmt::format("the best aligned hypothesis has {} inliers, {} needed",
                    acquisition.alignment.inliers, options.min_inliers);
    return acquisition;
  }
  const SearchSummary& summary = acquisition.summary;
  if (summary.best_score < options.min_verification_score) {
    acquisition.alignment.status = AlignmentStatus::kTooFewMatches;
    acquisition.alignment.message = fmt::format(
        "the best aligned hypothesis scores {:.1f}, below {:.1f}: too little of its model on the "
        "image's edges, or too many image edges in its open sky",
        summary.best_score, options.min_verification_score);
    return acquisition;
  }
  if (summary.rival_score >= options.ambiguous_score_fraction * summary.best_score) {
    acquisition.alignment.status = AlignmentStatus::kAmbiguous;
    acquisition.alignment.message =
        fmt::format("two distinct poses align: verification scores {:.1f} and {:.1f}",
                    summary.best_score, summary.rival_score);
  }
  return acquisition;
}

double verificationScore(const std::vector<ImageSegment>& segments,
                         const std::vector<ModelSegment>& lines, const OcclusionScene& scene,
                         const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera,
                         double sky_clutter_density, const AcquisitionOptions& options) {
  const ReferenceView view = searchedView(segments, camera, options);
  const std::vector<VisibleSegment> visible = visibleSegments(
      lines, scene, hypothesisStart(T_world_camera, options), view.camera, options.visibility);
  return verifiedScore(
      CoverageVerifier(view, options).coverage(visible, T_world_camera),
      measureSkyEdges(view.segments, T_world_camera, view.camera, scene, options.sky_edges),
      sky_clutter_density, options.sky_edges);
}

std::optional<ScoredHypothesis> alignHypothesis(
    const std::vector<ImageSegment>& segments, const std::vector<ModelSegment>& lines,
    const OcclusionScene& scene, const PoseWithCovariance& prior, const Eigen::Isometry3d& start,
    const PinholeCamera& camera, double sky_clutter_density, const AcquisitionOptions& options) {
  const ReferenceView view = searchedView(segments, camera, options);
  Verified candidate = alignFrom(view.segments, CoverageVerifier(view, options), lines, scene,
                                 prior, start, view.camera, options);
  if (!hasPose(candidate.alignment)) {
    return std::nullopt;
  }
  candidate.score =
      verifiedScore(candidate.coverage, candidate.sky, sky_clutter_density, options.sky_edges);
  return scored(candidate, options);
}

}  // namespace lineloc
