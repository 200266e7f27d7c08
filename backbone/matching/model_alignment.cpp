#include "backbone/matching/model_alignment.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>

#include "common/pose/pose_estimator.h"
#include "common/time/clock.h"

namespace lineloc {
namespace {

struct MatchedProblem {
  PoseProblem problem;
  std::vector<LineMatch> matches;
};

MatchedProblem buildProblem(const std::vector<ImageSegment>& image,
                            const std::vector<VisibleSegment>& model,
                            const std::vector<std::vector<LineMatch>>& candidates,
                            const PinholeCamera& camera, double ambiguity_margin_chi2) {
  MatchedProblem matched;
  matched.problem.camera = camera;
  for (const std::vector<LineMatch>& options : candidates) {
    if (options.empty()) {
      continue;
    }
    const bool ambiguous = options.size() > 1 &&
                           options[1].chi2 - options[0].chi2 < ambiguity_margin_chi2 &&
                           options[1].model_index != options[0].model_index;
    if (ambiguous) {
      continue;
    }
    const LineMatch& best = options.front();
    const ImageSegment& seen = image[best.image_index];
    const VisibleSegment& line = model[best.model_index];
    LineCorrespondence correspondence;
    correspondence.start_world = line.start_world;
    correspondence.end_world = line.end_world;
    correspondence.start_pixel = seen.start.cast<double>();
    correspondence.end_pixel = seen.end.cast<double>();
    // A model line seen through uncertain visibility counts for less: its
    // measurement variance is inflated by 1 / weight.
    correspondence.start_covariance = seen.start_covariance.cast<double>() / line.weight;
    correspondence.end_covariance = seen.end_covariance.cast<double>() / line.weight;
    matched.problem.lines.push_back(correspondence);
    matched.matches.push_back(best);
  }
  return matched;
}

double largestPositionSigma(const Matrix6d& covariance) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance.topLeftCorner<3, 3>());
  return std::sqrt(std::max(0.0, eigen.eigenvalues().maxCoeff()));
}

bool converged(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
               const AlignmentOptions& options) {
  const Eigen::AngleAxisd rotation(a.linear().transpose() * b.linear());
  return (a.translation() - b.translation()).norm() < options.converged_translation_m &&
         std::abs(rotation.angle()) < options.converged_rotation_rad;
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
  }
  return "unknown";
}

Alignment alignModel(const std::vector<ImageSegment>& image,
                     const std::vector<VisibleSegment>& model,
                     const PoseWithCovariance& predicted_T_world_camera,
                     const PinholeCamera& camera, const AlignmentOptions& options) {
  Alignment alignment;
  alignment.T_world_camera = predicted_T_world_camera;
  PoseWithCovariance current = predicted_T_world_camera;
  PoseOptions pose_options;
  pose_options.refinement.loss = RobustLoss::kCauchy;
  for (int round = 0; round < options.max_rounds; ++round) {
    alignment.rounds = round + 1;
    const int64_t matching_start_ns = steadyClockNs();
    const auto candidates = gateCandidates(image, model, current, camera, options.matching);
    const MatchedProblem matched =
        buildProblem(image, model, candidates, camera, options.ambiguity_margin_chi2);
    alignment.matching_ns += steadyClockNs() - matching_start_ns;
    alignment.matches = static_cast<int>(matched.matches.size());
    if (alignment.matches < options.min_inliers) {
      alignment.status = AlignmentStatus::kTooFewMatches;
      alignment.message =
          fmt::format("{} matches, {} needed", alignment.matches, options.min_inliers);
      return alignment;
    }
    pose_options.prior_T_world_camera = current.pose;
    const int64_t pose_start_ns = steadyClockNs();
    const PoseEstimate estimate = estimatePose(matched.problem, pose_options);
    alignment.pose_ns += steadyClockNs() - pose_start_ns;
    if (!estimate.ok()) {
      alignment.status = estimate.status == PoseStatus::kAmbiguous ? AlignmentStatus::kAmbiguous
                                                                   : AlignmentStatus::kFailed;
      alignment.message = fmt::format("pose: {} {}", toString(estimate.status), estimate.message);
      return alignment;
    }
    alignment.inliers = 0;
    for (const CorrespondenceResidual& residual : estimate.line_residuals) {
      alignment.inliers += residual.normalized_residual < options.inlier_threshold_sigma ? 1 : 0;
    }
    alignment.rms_residual_px = estimate.rms_residual_px;
    const bool done = converged(current.pose, estimate.T_world_camera.pose, options);
    current = estimate.T_world_camera;
    if (done) {
      break;
    }
  }
  alignment.T_world_camera = current;
  if (alignment.inliers < options.min_inliers) {
    alignment.status = AlignmentStatus::kTooFewMatches;
    alignment.message =
        fmt::format("{} inliers, {} needed", alignment.inliers, options.min_inliers);
    return alignment;
  }
  const double sigma = largestPositionSigma(current.covariance);
  if (!(sigma <= options.max_position_sigma_m)) {
    alignment.status = AlignmentStatus::kIllConditioned;
    alignment.message = fmt::format("position sigma {:.3f} m", sigma);
    return alignment;
  }
  alignment.status = AlignmentStatus::kOk;
  return alignment;
}

}  // namespace lineloc
