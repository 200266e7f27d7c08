#include "backbone/matching/localizer.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "common/time/clock.h"

namespace lineloc {

bool needsAcquisition(const PoseWithCovariance& prior, const LocalizerOptions& options) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> position(
      prior.covariance.topLeftCorner<3, 3>(), Eigen::EigenvaluesOnly);
  const double position_sigma_m = std::sqrt(std::max(0.0, position.eigenvalues().maxCoeff()));
  const double yaw_sigma_rad = std::sqrt(std::max(0.0, prior.covariance(5, 5)));
  return !(position_sigma_m <= options.max_tracking_position_sigma_m &&
           yaw_sigma_rad <= options.max_tracking_yaw_sigma_rad);
}

Localization localize(const std::vector<ImageSegment>& image,
                      const std::vector<ModelSegment>& lines, const OcclusionScene& scene,
                      const PoseWithCovariance& prior, const PinholeCamera& camera,
                      const LocalizerOptions& options) {
  Localization localization;
  if (needsAcquisition(prior, options)) {
    Acquisition acquisition = acquirePose(image, lines, scene, prior, camera, options.acquisition);
    localization.search = acquisition.summary;
    localization.alignment = std::move(acquisition.alignment);
    localization.visible = std::move(acquisition.visible);
    localization.visibility_ns = acquisition.summary.search_ns;
    return localization;
  }
  const int64_t visibility_start_ns = steadyClockNs();
  localization.visible = visibleSegments(lines, scene, prior, camera, options.visibility);
  localization.visibility_ns = steadyClockNs() - visibility_start_ns;
  PoseWithCovariance trusted_centre = prior;
  trusted_centre.covariance *= options.first_gate_scale * options.first_gate_scale;
  localization.alignment =
      alignModel(image, localization.visible, trusted_centre, camera, options.alignment);
  if (localization.alignment.status != AlignmentStatus::kOk) {
    const Alignment narrow = std::move(localization.alignment);
    localization.alignment =
        alignModel(image, localization.visible, prior, camera, options.alignment);
    localization.alignment.matching_ns += narrow.matching_ns;
    localization.alignment.pose_ns += narrow.pose_ns;
  }
  return localization;
}

}  // namespace lineloc
