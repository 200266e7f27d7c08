#include "backbone/matching/model_alignment.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <utility>

#include "common/pose/pose_estimator.h"
#include "common/stats/confidence_scale.h"
#include "common/time/clock.h"
#include "db/citymodel/line_extraction.h"

namespace lineloc {
namespace {

// The problem's lines are the matches, in order, and its points the corner
// matches.
struct MatchedProblem {
  PoseProblem problem;
  std::vector<LineMatch> matches;
  std::vector<CornerMatch> corner_matches;
};

// Survey error of a model line or vertex: a building's foot is less certain than the
// rest of it (AlignmentOptions::ground_line_sigma_m).
double modelSigmaM(bool on_ground, const AlignmentOptions& options) {
  return on_ground ? options.ground_line_sigma_m : options.model_sigma_m;
}

// A learnt line is never more certain than a surveyed one.
double modelSigmaM(const VisibleSegment& line, const AlignmentOptions& options) {
  if (line.kind == static_cast<int>(citymodel::LineKind::kLearnt)) {
    return std::max(line.sigma_m, options.model_sigma_m);
  }
  return modelSigmaM(line.kind == static_cast<int>(citymodel::LineKind::kGround), options);
}

// Isotropic pixel variance of edge bias and model error for a model point
// seen from the pose: floor^2 + (f sigma_model / z)^2.
Eigen::Matrix2d floorCovariance(const Eigen::Vector3d& point_world, double model_sigma_m,
                                const Eigen::Isometry3d& T_camera_world,
                                const PinholeCamera& camera, const AlignmentOptions& options) {
  const double depth_m = std::max((T_camera_world * point_world).z(), 1e-3);
  const double model_px = 0.5 * (camera.fx + camera.fy) * model_sigma_m / depth_m;
  const double variance =
      options.edge_sigma_floor_px * options.edge_sigma_floor_px + model_px * model_px;
  return variance * Eigen::Matrix2d::Identity();
}

// Mean over the seen segment's endpoints of their normal offset from the
// model line projected with the pose, towards the line's façade side, in
// standard deviations of the correspondence: n_f . (q_i - l) / sqrt(n_f^T
// Sigma_i n_f), n_f the unit normal on the façade's side.
double facadeSideOffsetSigma(const LineCorrespondence& correspondence, int facade_side,
                             const Eigen::Isometry3d& T_camera_world, const PinholeCamera& camera) {
  const Eigen::Vector2d start_px = camera.project(T_camera_world * correspondence.start_world);
  const Eigen::Vector2d direction =
      (camera.project(T_camera_world * correspondence.end_world) - start_px).normalized();
  // The left normal (image, y down) of direction (dx, dy) is (dy, -dx).
  const Eigen::Vector2d towards_facade =
      facade_side * Eigen::Vector2d(direction.y(), -direction.x());
  const auto offsetSigma = [&](const Eigen::Vector2d& pixel, const Eigen::Matrix2d& covariance) {
    return towards_facade.dot(pixel - start_px) /
           std::sqrt(towards_facade.dot(covariance * towards_facade));
  };
  return 0.5 * (offsetSigma(correspondence.start_pixel, correspondence.start_covariance) +
                offsetSigma(correspondence.end_pixel, correspondence.end_covariance));
}

// Each matched corner as a point correspondence, its covariance the image
// corner's plus the floor, inflated by 1 / weight as a line's.
void addCorners(const AlignmentFeatures& features, std::vector<CornerMatch> corner_matches,
                const Eigen::Isometry3d& T_camera_world, const PinholeCamera& camera,
                const AlignmentOptions& options, MatchedProblem& matched) {
  for (const CornerMatch& match : corner_matches) {
    const ImageCorner& seen = features.image_corners[match.image_index];
    const VisibleCorner& vertex = features.model_corners[match.model_index];
    const double model_sigma_m = modelSigmaM(vertex.on_ground, options);
    PointCorrespondence correspondence;
    correspondence.p_world = vertex.p_world;
    correspondence.pixel = seen.position.cast<double>();
    correspondence.covariance =
        (seen.covariance.cast<double>() +
         floorCovariance(vertex.p_world, model_sigma_m, T_camera_world, camera, options)) /
        vertex.weight;
    matched.problem.points.push_back(correspondence);
  }
  matched.corner_matches = std::move(corner_matches);
}

MatchedProblem buildProblem(const AlignmentFeatures& features,
                            const std::vector<std::vector<LineMatch>>& candidates,
                            const std::vector<CornerMatch>& corner_matches,
                            const Eigen::Isometry3d& T_world_camera, const PinholeCamera& camera,
                            bool cut_facade_side, const AlignmentOptions& options) {
  MatchedProblem matched;
  matched.problem.camera = camera;
  const Eigen::Isometry3d T_camera_world = T_world_camera.inverse();
  for (const std::vector<LineMatch>& gated : candidates) {
    if (gated.empty()) {
      continue;
    }
    const bool ambiguous = gated.size() > 1 &&
                           gated[1].chi2 - gated[0].chi2 < options.ambiguity_margin_chi2 &&
                           gated[1].model_index != gated[0].model_index;
    if (ambiguous) {
      continue;
    }
    const LineMatch& best = gated.front();
    const ImageSegment& seen = features.image_segments[best.image_index];
    const VisibleSegment& line = features.model_segments[best.model_index];
    LineCorrespondence correspondence;
    correspondence.start_world = line.start_world;
    correspondence.end_world = line.end_world;
    correspondence.start_pixel = seen.start.cast<double>();
    correspondence.end_pixel = seen.end.cast<double>();
    // A model line seen through uncertain visibility counts for less: its
    // measurement variance is inflated by 1 / weight.
    const double model_sigma_m = modelSigmaM(line, options);
    correspondence.start_covariance =
        (seen.start_covariance.cast<double>() +
         floorCovariance(line.start_world, model_sigma_m, T_camera_world, camera, options)) /
        line.weight;
    correspondence.end_covariance =
        (seen.end_covariance.cast<double>() +
         floorCovariance(line.end_world, model_sigma_m, T_camera_world, camera, options)) /
        line.weight;
    if (cut_facade_side && line.facade_side != 0 &&
        facadeSideOffsetSigma(correspondence, line.facade_side, T_camera_world, camera) >
            options.facade_side_cut_sigma) {
      continue;
    }
    matched.problem.lines.push_back(correspondence);
    matched.matches.push_back(best);
  }
  addCorners(features, corner_matches, T_camera_world, camera, options, matched);
  return matched;
}

// The a-posteriori variance factor s^2 = chi^2 / (2 n - 6) of n line or
// corner correspondences (two residuals each, six pose parameters), when the
// residuals are larger than their stated noise; 1 otherwise, or with too few.
double varianceFactor(double chi2, int correspondences) {
  const int redundancy = 2 * correspondences - 6;
  return redundancy > 0 ? std::max(1.0, chi2 / redundancy) : 1.0;
}

// True when two model segments are one physical edge to the camera: the
// pieces of one model line, or parallel lines within coincident_m of each
// other (the two creases of a footprint jog a few centimetres deep, of which
// the image shows one edge).
bool sameEdge(const VisibleSegment& a, const VisibleSegment& b, double coincident_m) {
  if (a.model_line_id == b.model_line_id) {
    return true;
  }
  const Eigen::Vector3d direction = (a.end_world - a.start_world).normalized();
  const auto offset = [&](const Eigen::Vector3d& point) {
    const Eigen::Vector3d relative = point - a.start_world;
    return (relative - direction.dot(relative) * direction).norm();
  };
  return offset(b.start_world) < coincident_m && offset(b.end_world) < coincident_m;
}

// Group of each correspondence for the jackknife: correspondences whose
// model segments are one edge (sameEdge) share its error and are left out
// together.
std::vector<int> edgeGroups(const std::vector<LineMatch>& matches,
                            const std::vector<VisibleSegment>& model, double coincident_m) {
  std::vector<int> groups(matches.size());
  for (size_t i = 0; i < matches.size(); ++i) {
    groups[i] = static_cast<int>(i);
    for (size_t j = 0; j < i; ++j) {
      if (sameEdge(model[matches[j].model_index], model[matches[i].model_index], coincident_m)) {
        groups[i] = groups[j];
        break;
      }
    }
  }
  return groups;
}

bool converged(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
               const AlignmentOptions& options) {
  const Eigen::AngleAxisd rotation(a.linear().transpose() * b.linear());
  return (a.translation() - b.translation()).norm() < options.converged_translation_m &&
         std::abs(rotation.angle()) < options.converged_rotation_rad;
}

PoseOptions refinementOptions(const AlignmentOptions& options) {
  PoseOptions pose_options;
  pose_options.refinement.loss = RobustLoss::kCauchy;
  pose_options.refinement.loss_scale = options.loss_scale_sigma;
  pose_options.refinement.function_tolerance = options.function_tolerance;
  pose_options.refinement.parameter_tolerance = options.parameter_tolerance;
  pose_options.refinement.step_information_tolerance = options.step_information_tolerance;
  return pose_options;
}

// One round from `gate`: candidates gated there, each image segment's best
// kept (less those on their façade's side when cut_facade_side), and the pose
// refined from the gate's centre without weighing it. The alignment takes the
// round's matches, inliers, residual and time, and its pose, the covariance
// scaled by the inliers' variance factor. False, with the status and message
// set and the pose left alone, when too few matches or the refinement fails.
bool alignRound(const AlignmentFeatures& features, const PoseWithCovariance& gate,
                const PinholeCamera& camera, bool cut_facade_side, const AlignmentOptions& options,
                Alignment& alignment, MatchedProblem& matched) {
  ++alignment.rounds;
  const int64_t matching_start_ns = steadyClockNs();
  const auto candidates = gateCandidates(features.image_segments, features.model_segments, gate,
                                         camera, options.matching);
  matched = buildProblem(
      features, candidates,
      matchCorners(features.image_corners, features.model_corners, gate, camera, options.corners),
      gate.pose, camera, cut_facade_side, options);
  alignment.matching_ns += steadyClockNs() - matching_start_ns;
  alignment.matches = static_cast<int>(matched.matches.size() + matched.corner_matches.size());
  if (alignment.matches < options.min_inliers) {
    alignment.status = AlignmentStatus::kTooFewMatches;
    alignment.message =
        fmt::format("{} matches, {} needed", alignment.matches, options.min_inliers);
    return false;
  }
  PoseOptions pose_options = refinementOptions(options);
  pose_options.prior_T_world_camera = gate.pose;
  const int64_t pose_start_ns = steadyClockNs();
  const PoseEstimate estimate = estimatePose(matched.problem, pose_options);
  alignment.pose_ns += steadyClockNs() - pose_start_ns;
  if (!estimate.ok()) {
    alignment.status = estimate.status == PoseStatus::kAmbiguous ? AlignmentStatus::kAmbiguous
                                                                 : AlignmentStatus::kFailed;
    alignment.message = fmt::format("pose: {} {}", toString(estimate.status), estimate.message);
    return false;
  }
  alignment.inliers = 0;
  alignment.inlier_corners.clear();
  double inlier_chi2 = 0.0;
  for (const auto* residuals : {&estimate.line_residuals, &estimate.point_residuals}) {
    for (size_t i = 0; i < residuals->size(); ++i) {
      const double normalized = (*residuals)[i].normalized_residual;
      if (normalized < options.inlier_threshold_sigma) {
        ++alignment.inliers;
        inlier_chi2 += normalized * normalized;
        if (residuals == &estimate.point_residuals) {
          alignment.inlier_corners.push_back(matched.corner_matches[i].image_index);
        }
      }
    }
  }
  alignment.rms_residual_px = estimate.rms_residual_px;
  alignment.T_world_camera = estimate.T_world_camera;
  alignment.T_world_camera.covariance *= varianceFactor(inlier_chi2, alignment.inliers);
  return true;
}

// The status of the last round's pose: OK when enough inliers carry it and,
// its covariance grown to cover the jackknife over model edges, it leaves the
// position within max_position_sigma_m.
void conclude(const MatchedProblem& last_round, const std::vector<VisibleSegment>& model,
              const AlignmentOptions& options, Alignment& alignment) {
  if (alignment.inliers < options.min_inliers) {
    alignment.status = AlignmentStatus::kTooFewMatches;
    alignment.message =
        fmt::format("{} inliers, {} needed", alignment.inliers, options.min_inliers);
    return;
  }
  const int64_t jackknife_start_ns = steadyClockNs();
  const Matrix6d jackknife =
      leaveGroupOutCovariance(last_round.problem, alignment.T_world_camera.pose,
                              edgeGroups(last_round.matches, model, options.coincident_edge_m),
                              refinementOptions(options).refinement);
  alignment.pose_ns += steadyClockNs() - jackknife_start_ns;
  if (!jackknife.allFinite()) {
    alignment.status = AlignmentStatus::kIllConditioned;
    alignment.message = "one model line alone determines part of the pose";
    return;
  }
  alignment.T_world_camera.covariance =
      coveringCovariance(alignment.T_world_camera.covariance, jackknife);
  const double sigma = largestPositionSigma(alignment.T_world_camera.covariance);
  if (!(sigma <= options.max_position_sigma_m)) {
    alignment.status = AlignmentStatus::kIllConditioned;
    alignment.message = fmt::format("position sigma {:.3f} m", sigma);
    return;
  }
  alignment.status = AlignmentStatus::kOk;
}

// Rounds from `first_gate` until the pose stops moving, at most max_rounds,
// without the cut; each later round gates at the prediction fused with the
// last pose. A round that fails leaves the predicted pose.
Alignment alignRounds(const AlignmentFeatures& features,
                      const PoseWithCovariance& predicted_T_world_camera,
                      const PoseWithCovariance& first_gate, const PinholeCamera& camera,
                      const AlignmentOptions& options) {
  Alignment alignment;
  alignment.T_world_camera = predicted_T_world_camera;
  alignment.next_gate = first_gate;
  MatchedProblem last_round;
  for (int round = 0; round < options.max_rounds; ++round) {
    const Eigen::Isometry3d previous = alignment.T_world_camera.pose;
    if (!alignRound(features, alignment.next_gate, camera, false, options, alignment, last_round)) {
      alignment.T_world_camera = predicted_T_world_camera;
      return alignment;
    }
    alignment.next_gate = alignment.T_world_camera.covariance.allFinite()
                              ? fusePoses(predicted_T_world_camera, alignment.T_world_camera)
                              : predicted_T_world_camera;
    if (converged(previous, alignment.T_world_camera.pose, options)) {
      break;
    }
  }
  conclude(last_round, features.model_segments, options, alignment);
  return alignment;
}

// The segments alone, without corners.
AlignmentFeatures lineFeatures(const std::vector<ImageSegment>& image,
                               const std::vector<VisibleSegment>& model) {
  static const std::vector<ImageCorner> kNoImageCorners;
  static const std::vector<VisibleCorner> kNoModelCorners;
  return {image, kNoImageCorners, model, kNoModelCorners};
}

}  // namespace

const char* toString(AlignmentStatus status) {
  switch (status) {
    case AlignmentStatus::kOk:
      return "ok";
    case AlignmentStatus::kTooFewMatches:
      return "too_few_matches";
    case AlignmentStatus::kIllConditioned:
      return "ill_conditioned";
    case AlignmentStatus::kAmbiguous:
      return "ambiguous";
    case AlignmentStatus::kFailed:
      return "failed";
    case AlignmentStatus::kInconsistent:
      return "inconsistent";
  }
  return "unknown";
}

Alignment alignModel(const std::vector<ImageSegment>& image,
                     const std::vector<VisibleSegment>& model,
                     const PoseWithCovariance& predicted_T_world_camera,
                     const PinholeCamera& camera, const AlignmentOptions& options) {
  return leaveOutFacadeSideDetail(alignRounds(lineFeatures(image, model), predicted_T_world_camera,
                                              predicted_T_world_camera, camera, options),
                                  image, model, camera, options);
}

Alignment completeWithCorners(const Alignment& lines, const AlignmentFeatures& features,
                              const PoseWithCovariance& predicted_T_world_camera,
                              const PinholeCamera& camera, const AlignmentOptions& options) {
  if ((lines.status != AlignmentStatus::kIllConditioned &&
       lines.status != AlignmentStatus::kTooFewMatches) ||
      features.image_corners.empty() || features.model_corners.empty()) {
    return lines;
  }
  Alignment completed =
      alignRounds(features, predicted_T_world_camera, lines.next_gate, camera, options);
  Alignment answer = completed.status == AlignmentStatus::kOk ? completed : lines;
  answer.rounds = lines.rounds + completed.rounds;
  answer.matching_ns = lines.matching_ns + completed.matching_ns;
  answer.pose_ns = lines.pose_ns + completed.pose_ns;
  return answer;
}

Alignment leaveOutFacadeSideDetail(const Alignment& aligned, const std::vector<ImageSegment>& image,
                                   const std::vector<VisibleSegment>& model,
                                   const PinholeCamera& camera, const AlignmentOptions& options) {
  if (aligned.status != AlignmentStatus::kOk || !std::isfinite(options.facade_side_cut_sigma)) {
    return aligned;
  }
  Alignment cut = aligned;
  MatchedProblem last_round;
  if (alignRound(lineFeatures(image, model), aligned.next_gate, camera, true, options, cut,
                 last_round)) {
    conclude(last_round, model, options, cut);
  }
  if (cut.status == AlignmentStatus::kOk) {
    return cut;
  }
  Alignment kept = aligned;
  kept.rounds = cut.rounds;
  kept.matching_ns = cut.matching_ns;
  kept.pose_ns = cut.pose_ns;
  return kept;
}

void widenForConfidence(Alignment& alignment, double confidence) {
  if (alignment.status == AlignmentStatus::kOk) {
    alignment.T_world_camera.covariance *=
        confidenceScale(std::max(1, 2 * alignment.inliers - 6), confidence);
  }
}

}  // namespace lineloc
