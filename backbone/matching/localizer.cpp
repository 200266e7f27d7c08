#include "backbone/matching/localizer.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/parallel/parallel_for.h"
#include "common/time/clock.h"

namespace lineloc {
namespace {

// The prior and its sigma points: the centre moved by +-k sigma along each
// principal axis of the position covariance, at least min_step_m along the
// horizontal ones, and turned by +-k sigma_yaw about the world vertical (the
// error convention's dtheta_z). Each keeps the prior's covariance, widened
// along its axis to sigma = step / k where the step was floored.
std::vector<PoseWithCovariance> trackingStarts(const PoseWithCovariance& prior, double k,
                                               double min_step_m) {
  std::vector<PoseWithCovariance> starts = {prior};
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> position(
      prior.covariance.topLeftCorner<3, 3>());
  const double yaw_step_rad = k * std::sqrt(std::max(0.0, prior.covariance(5, 5)));
  for (const double sign : {-1.0, 1.0}) {
    for (int axis = 0; axis < 3; ++axis) {
      const double sigma_m = std::sqrt(std::max(0.0, position.eigenvalues()[axis]));
      const Eigen::Vector3d direction = position.eigenvectors().col(axis);
      const bool horizontal = std::abs(direction.z()) < M_SQRT1_2;
      const double step_m = horizontal ? std::max(k * sigma_m, min_step_m) : k * sigma_m;
      PoseWithCovariance moved = prior;
      moved.pose.translation() += sign * step_m * direction;
      moved.covariance.topLeftCorner<3, 3>() +=
          (step_m * step_m / (k * k) - sigma_m * sigma_m) * direction * direction.transpose();
      starts.push_back(moved);
    }
    PoseWithCovariance turned = prior;
    turned.pose.linear() =
        Eigen::AngleAxisd(sign * yaw_step_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
        prior.pose.linear();
    starts.push_back(turned);
  }
  return starts;
}

// Narrow gates around the start's centre first; its whole covariance when
// they do not give an OK alignment.
Alignment alignFromCentre(const AlignmentFeatures& features, const PoseWithCovariance& start,
                          const PinholeCamera& camera, const LocalizerOptions& options) {
  PoseWithCovariance trusted_centre = start;
  trusted_centre.covariance *= options.first_gate_scale * options.first_gate_scale;
  Alignment narrow = alignModel(features.image_segments, features.model_segments, trusted_centre,
                                camera, options.alignment);
  if (narrow.status == AlignmentStatus::kOk) {
    return narrow;
  }
  Alignment wide = alignModel(features.image_segments, features.model_segments, start, camera,
                              options.alignment);
  wide.matching_ns += narrow.matching_ns;
  wide.pose_ns += narrow.pose_ns;
  return wide;
}

// True when `pose` lies within distinct_chi2 of `centre` in `covariance`:
// e^T C^-1 e <= chi2, e = pose's error from centre (pose.h).
bool within(const Eigen::Isometry3d& centre, const Matrix6d& covariance,
            const Eigen::Isometry3d& pose, const LocalizerOptions& options) {
  return normalizedErrorSquared({centre, covariance}, pose) <= options.distinct_chi2;
}

// True when `other` lies beyond distinct_chi2 of `answer` in answer's own covariance.
bool outside(const Alignment& answer, const Alignment& other, const LocalizerOptions& options) {
  return !within(answer.T_world_camera.pose, answer.T_world_camera.covariance,
                 other.T_world_camera.pose, options);
}

bool isOk(const Alignment& alignment) {
  return alignment.status == AlignmentStatus::kOk;
}

// An alignment that settled on a pose: OK, or ill-conditioned (it fits the
// image, but its covariance is too wide to answer with).
bool settled(const Alignment& alignment) {
  return isOk(alignment) || alignment.status == AlignmentStatus::kIllConditioned;
}

// Each alignment's coverage of the image by the visible model lines
// (pose_acquisition.h), against a sharp distance map.
std::vector<double> coverageScores(const std::vector<Alignment>& aligned,
                                   const std::vector<ImageSegment>& image,
                                   const std::vector<VisibleSegment>& visible,
                                   const PinholeCamera& camera, const LocalizerOptions& options) {
  const CoverageVerifier verifier(image, camera, options.acquisition);
  std::vector<double> scores;
  for (const Alignment& alignment : aligned) {
    scores.push_back(verifier.coverage(visible, alignment.T_world_camera.pose).score);
  }
  return scores;
}

// The index of the best covered OK alignment, by coverage `scores`, or of the
// OK alignment with the most inliers in its basin (each within the other's
// covariance): the scores of one basin's alignments differ by noise, and the
// one that kept more matches estimated the pose from more of the evidence.
size_t bestCovered(const std::vector<Alignment>& aligned, const std::vector<double>& scores,
                   const LocalizerOptions& options) {
  size_t best = aligned.size();
  for (size_t i = 0; i < aligned.size(); ++i) {
    if (isOk(aligned[i]) && (best == aligned.size() || scores[i] > scores[best])) {
      best = i;
    }
  }
  size_t chosen = best;
  for (size_t i = 0; i < aligned.size() && best < aligned.size(); ++i) {
    if (isOk(aligned[i]) && aligned[i].inliers > aligned[chosen].inliers &&
        !outside(aligned[best], aligned[i], options) &&
        !outside(aligned[i], aligned[best], options)) {
      chosen = i;
    }
  }
  return chosen;
}

// The answer, its covariance grown by d d^T for every settled rival covered
// at least rival_score_fraction as well as the answer's start (best_score) and
// outside it (d the rival's offset); kAmbiguous when that leaves a position
// sigma beyond the alignment's limit.
Alignment coverRivals(Alignment answer, const std::vector<Alignment>& aligned,
                      const std::vector<double>& scores, double best_score,
                      const LocalizerOptions& options) {
  const Eigen::Isometry3d answer_pose = answer.T_world_camera.pose;
  const Matrix6d answer_covariance = answer.T_world_camera.covariance;
  int rivals = 0;
  for (size_t i = 0; i < aligned.size(); ++i) {
    if (scores[i] < options.rival_score_fraction * best_score ||
        within(answer_pose, answer_covariance, aligned[i].T_world_camera.pose, options)) {
      continue;
    }
    const Eigen::Matrix<double, 6, 1> offset =
        poseError(answer_pose, aligned[i].T_world_camera.pose);
    answer.T_world_camera.covariance += offset * offset.transpose();
    ++rivals;
  }
  const double sigma_m = largestPositionSigma(answer.T_world_camera.covariance);
  if (sigma_m > options.alignment.max_position_sigma_m) {
    answer.status = AlignmentStatus::kAmbiguous;
    answer.message = fmt::format(
        "{} rival alignments from the prior's sigma points leave a position sigma of {:.2f} m",
        rivals, sigma_m);
  }
  return answer;
}

// True when an alignment lies within distinct_chi2 of its start in the sum
// of their covariances.
bool reaches(const PoseWithCovariance& start, const Alignment& alignment,
             const LocalizerOptions& options) {
  return within(start.pose, start.covariance + alignment.T_world_camera.covariance,
                alignment.T_world_camera.pose, options);
}

// The alignment from one start, kInconsistent when it is OK but out of the
// start's reach.
Alignment alignWithinReach(const AlignmentFeatures& features, const PoseWithCovariance& start,
                           const PinholeCamera& camera, const LocalizerOptions& options) {
  Alignment alignment = alignFromCentre(features, start, camera, options);
  if (isOk(alignment) && !reaches(start, alignment, options)) {
    alignment.status = AlignmentStatus::kInconsistent;
    alignment.message =
        fmt::format("aligned {:.2f} m from its start, beyond chi^2_6 = {:.2f} of their covariances",
                    (alignment.T_world_camera.pose.translation() - start.pose.translation()).norm(),
                    options.distinct_chi2);
  }
  return alignment;
}

// The centre's ill-conditioned alignment completed with the corners
// (completeWithCorners) when that is OK and within the prior's reach; the
// lines' alignment, with the completion's time, otherwise.
Alignment completeWithinReach(const Alignment& centre, const AlignmentFeatures& features,
                              const PoseWithCovariance& prior, const PinholeCamera& camera,
                              const LocalizerOptions& options) {
  const Alignment completed =
      completeWithCorners(centre, features, prior, camera, options.alignment);
  if (isOk(completed) && reaches(prior, completed, options)) {
    return completed;
  }
  Alignment lines = centre;
  lines.matching_ns = completed.matching_ns;
  lines.pose_ns = completed.pose_ns;
  return lines;
}

// The settled alignments from the prior and its sigma points, the OK ones
// within reach of their start: the first OK one when every other lies within
// its covariance, else the best covered, with its rivals (coverRivals). The
// centre's own answer when it is ill-conditioned or none is OK. The starts
// align without the façade-side cut; the OK one answered takes it
// (leaveOutFacadeSideDetail), before its rivals widen it.
Alignment track(const AlignmentFeatures& features, const PoseWithCovariance& prior,
                const PinholeCamera& camera, const LocalizerOptions& options) {
  const std::vector<PoseWithCovariance> starts =
      trackingStarts(prior, options.start_sigma, options.min_start_step_m);
  LocalizerOptions uncut = options;
  uncut.alignment.facade_side_cut_sigma = std::numeric_limits<double>::infinity();
  std::vector<Alignment> from_starts(starts.size());
  const int64_t aligning_start_ns = steadyClockNs();
  parallelFor(static_cast<int>(starts.size()), options.threads, [&](int i) {
    from_starts[i] = alignWithinReach(features, starts[i], camera, uncut);
  });
  const int64_t aligning_ns = steadyClockNs() - aligning_start_ns;
  const Alignment& centre = from_starts.front();
  std::vector<Alignment> aligned;
  int64_t matching_cpu_ns = 0;
  int64_t pose_cpu_ns = 0;
  for (const Alignment& alignment : from_starts) {
    matching_cpu_ns += alignment.matching_ns;
    pose_cpu_ns += alignment.pose_ns;
    if (settled(alignment)) {
      aligned.push_back(alignment);
    }
  }
  // The threads' wall time, shared between the stages as their CPU time is.
  const double matching_share =
      static_cast<double>(matching_cpu_ns) / std::max<int64_t>(1, matching_cpu_ns + pose_cpu_ns);
  int64_t matching_ns = std::llround(matching_share * aligning_ns);
  int64_t pose_ns = aligning_ns - matching_ns;
  const auto first_ok = std::find_if(aligned.begin(), aligned.end(), isOk);
  Alignment answer = centre;
  if (first_ok != aligned.end() && centre.status != AlignmentStatus::kIllConditioned) {
    const auto outsideFirst = [&](const Alignment& other) {
      return outside(*first_ok, other, options);
    };
    const bool agree = std::none_of(aligned.begin(), aligned.end(), outsideFirst);
    const int64_t scoring_start_ns = steadyClockNs();
    const std::vector<double> scores =
        agree ? std::vector<double>{}
              : coverageScores(aligned, features.image_segments, features.model_segments, camera,
                               options);
    matching_ns += steadyClockNs() - scoring_start_ns;
    const size_t chosen =
        agree ? first_ok - aligned.begin() : bestCovered(aligned, scores, options);
    answer = leaveOutFacadeSideDetail(aligned[chosen], features.image_segments,
                                      features.model_segments, camera, options.alignment);
    matching_ns += answer.matching_ns - aligned[chosen].matching_ns;
    pose_ns += answer.pose_ns - aligned[chosen].pose_ns;
    if (!agree) {
      answer = coverRivals(answer, aligned, scores, scores[chosen], options);
    }
  }
  if (answer.status == AlignmentStatus::kIllConditioned ||
      answer.status == AlignmentStatus::kTooFewMatches) {
    answer = completeWithinReach(answer, features, prior, camera, options);
    matching_ns += answer.matching_ns - centre.matching_ns;
    pose_ns += answer.pose_ns - centre.pose_ns;
  }
  answer.matching_ns = matching_ns;
  answer.pose_ns = pose_ns;
  return answer;
}

}  // namespace

bool needsAcquisition(const PoseWithCovariance& prior, const LocalizerOptions& options) {
  const double yaw_sigma_rad = std::sqrt(std::max(0.0, prior.covariance(5, 5)));
  return !(largestPositionSigma(prior.covariance) <= options.max_tracking_position_sigma_m &&
           yaw_sigma_rad <= options.max_tracking_yaw_sigma_rad);
}

PoseWithCovariance narrowedForTracking(const PoseWithCovariance& prior,
                                       const LocalizerOptions& options) {
  const double yaw_sigma_rad = std::sqrt(std::max(0.0, prior.covariance(5, 5)));
  const double excess =
      std::max(largestPositionSigma(prior.covariance) / options.max_tracking_position_sigma_m,
               yaw_sigma_rad / options.max_tracking_yaw_sigma_rad);
  PoseWithCovariance narrowed = prior;
  if (excess > 1.0) {
    // A hair under the limits, which needsAcquisition compares with <=.
    narrowed.covariance /= std::pow(excess * (1.0 + 1e-6), 2);
  }
  return narrowed;
}

std::vector<VisibleSegment> visibleFromPrior(const std::vector<ModelSegment>& lines,
                                             const OcclusionScene& scene,
                                             const PoseWithCovariance& prior,
                                             const PinholeCamera& camera,
                                             const LocalizerOptions& options) {
  VisibilityOptions visibility = options.visibility;
  visibility.threads = options.threads;
  return visibleSegments(lines, scene, prior, camera, visibility);
}

Localization localize(const std::vector<ImageSegment>& image_segments,
                      const std::vector<ImageCorner>& image_corners,
                      const std::vector<ModelSegment>& lines, const OcclusionScene& scene,
                      const PoseWithCovariance& prior, const PinholeCamera& camera,
                      const LocalizerOptions& options,
                      const std::vector<VisibleSegment>* visible_from_prior) {
  Localization localization;
  if (needsAcquisition(prior, options)) {
    Acquisition acquisition =
        acquirePose(image_segments, lines, scene, prior, camera, options.acquisition);
    localization.search = acquisition.summary;
    localization.alignment = std::move(acquisition.alignment);
    localization.visible = std::move(acquisition.visible);
    localization.visibility_ns = acquisition.summary.search_ns;
    return localization;
  }
  const int64_t visibility_start_ns = steadyClockNs();
  localization.visible = visible_from_prior
                             ? *visible_from_prior
                             : visibleFromPrior(lines, scene, prior, camera, options);
  const std::vector<VisibleCorner> visible_corners =
      visibleCorners(localization.visible, options.corners);
  localization.visibility_ns = steadyClockNs() - visibility_start_ns;
  localization.alignment =
      track({image_segments, image_corners, localization.visible, visible_corners}, prior, camera,
            options);
  widenForConfidence(localization.alignment, options.alignment.confidence);
  return localization;
}

}  // namespace lineloc
