#include "robot/calibration/zhang_calibration.h"

#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "common/camera/lens_distortion.h"
#include "common/homography/homography.h"
#include "robot/calibration/closed_form_intrinsics.h"
#include "robot/calibration/distortion_initialisation.h"
#include "robot/calibration/planar_extrinsics.h"

namespace lineloc {

namespace {

// Views whose plane normals all lie within this angle add no constraint on K
// beyond one view (Zhang §3.1): warn below it.
constexpr double kParallelPlanesAngleRad = 5.0 * M_PI / 180.0;
// Fraction of an image grid's cells that some view's pattern covers, below
// which the distortion is extrapolated over much of the image: warn below it.
constexpr double kMinImageCoverage = 0.4;
constexpr int kCoverageGridCells = 20;

void validate(const PlanarViews& views) {
  if (views.image_width <= 0 || views.image_height <= 0) {
    throw std::invalid_argument("calibration: the image size must be positive");
  }
  const auto finite = [](const Eigen::Vector2d& p) { return p.allFinite(); };
  if (!std::all_of(views.model_points.begin(), views.model_points.end(), finite)) {
    throw std::invalid_argument("calibration: the model has non-finite points");
  }
  for (size_t view = 0; view < views.image_points.size(); ++view) {
    const std::vector<Eigen::Vector2d>& points = views.image_points[view];
    if (points.size() != views.model_points.size()) {
      throw std::invalid_argument(fmt::format("calibration: view {} has {} points, the model {}",
                                              view, points.size(), views.model_points.size()));
    }
    if (!std::all_of(points.begin(), points.end(), finite)) {
      throw std::invalid_argument(fmt::format("calibration: view {} has non-finite points", view));
    }
  }
}

CalibrationResult failure(CalibrationStatus status, std::string message) {
  CalibrationResult result;
  result.status = status;
  result.message = std::move(message);
  return result;
}

// Largest angle between two views' plane normals (the model z axis in the camera).
double largestNormalAngle(const std::vector<Eigen::Isometry3d>& T_camera_model) {
  double largest = 0.0;
  for (size_t a = 0; a < T_camera_model.size(); ++a) {
    for (size_t b = a + 1; b < T_camera_model.size(); ++b) {
      const double cosine =
          T_camera_model[a].linear().col(2).dot(T_camera_model[b].linear().col(2));
      largest = std::max(largest, std::acos(std::clamp(cosine, -1.0, 1.0)));
    }
  }
  return largest;
}

// Fraction of the cells of a grid over the image whose centre lies inside the
// convex hull of some view's points.
double imageCoverage(const PlanarViews& views) {
  std::vector<std::vector<cv::Point2f>> hulls;
  for (const std::vector<Eigen::Vector2d>& points : views.image_points) {
    std::vector<cv::Point2f> cv_points;
    for (const Eigen::Vector2d& p : points) {
      cv_points.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
    }
    hulls.emplace_back();
    cv::convexHull(cv_points, hulls.back());
  }
  int covered = 0;
  for (int row = 0; row < kCoverageGridCells; ++row) {
    for (int col = 0; col < kCoverageGridCells; ++col) {
      const cv::Point2f centre((col + 0.5f) * views.image_width / kCoverageGridCells,
                               (row + 0.5f) * views.image_height / kCoverageGridCells);
      covered += std::any_of(hulls.begin(), hulls.end(), [&](const auto& hull) {
        return cv::pointPolygonTest(hull, centre, false) >= 0.0;
      });
    }
  }
  return static_cast<double>(covered) / (kCoverageGridCells * kCoverageGridCells);
}

std::vector<std::string> degeneracyWarnings(const PlanarViews& views,
                                            const std::vector<Eigen::Isometry3d>& T_camera_model) {
  std::vector<std::string> warnings;
  if (views.image_points.size() < 3) {
    warnings.push_back(fmt::format("only {} views: at least 3 are needed to determine K",
                                   views.image_points.size()));
  }
  const double angle = largestNormalAngle(T_camera_model);
  if (angle < kParallelPlanesAngleRad) {
    warnings.push_back(fmt::format(
        "the pattern planes are nearly parallel in all views (largest angle {:.1f} deg): tilt "
        "the pattern differently between views",
        angle * 180.0 / M_PI));
  }
  const double coverage = imageCoverage(views);
  if (coverage < kMinImageCoverage) {
    warnings.push_back(fmt::format(
        "the pattern covers only {:.0f} % of the image over all views: distortion far from it "
        "is extrapolated",
        100.0 * coverage));
  }
  return warnings;
}

CalibrationStatus statusOf(RefinementStatus status) {
  switch (status) {
    case RefinementStatus::kConverged:
      return CalibrationStatus::kConverged;
    case RefinementStatus::kNoConvergence:
      return CalibrationStatus::kNoConvergence;
    case RefinementStatus::kDiverged:
      break;
  }
  return CalibrationStatus::kDiverged;
}

CalibrationResult resultOf(const PlanarViews& views, const RefinementResult& refinement) {
  CalibrationResult result;
  result.status = statusOf(refinement.status);
  if (result.status == CalibrationStatus::kDiverged) {
    result.message = "the maximum-likelihood refinement diverged";
    return result;
  }
  if (result.status == CalibrationStatus::kNoConvergence) {
    result.message = fmt::format("no convergence after {} iterations", refinement.iterations);
  }
  result.state = refinement.state;
  result.uncertainty = refinement.uncertainty;
  result.residuals_px = reprojectionResiduals(views, result.state);
  std::vector<Eigen::Vector2d> all;
  for (const std::vector<Eigen::Vector2d>& residuals : result.residuals_px) {
    result.per_view_rms_error_px.push_back(rmsError(residuals));
    all.insert(all.end(), residuals.begin(), residuals.end());
  }
  result.rms_error_px = rmsError(all);
  return result;
}

// K from the closed form with the options' constraints imposed on it.
PinholeCamera constrainedCamera(const Eigen::Matrix3d& K, const PlanarViews& views,
                                const CalibrationOptions& options) {
  PinholeCamera camera;
  camera.width = views.image_width;
  camera.height = views.image_height;
  camera.fx = K(0, 0);
  camera.fy = K(1, 1);
  camera.cx = K(0, 2);
  camera.cy = K(1, 2);
  camera.skew = options.fix_skew ? 0.0 : K(0, 1);
  if (options.fix_aspect_ratio) {
    camera.fy = 0.5 * (camera.fy + camera.fx / options.aspect_ratio);
    camera.fx = options.aspect_ratio * camera.fy;
  }
  if (options.fix_principal_point) {
    camera.cx = 0.5 * (views.image_width - 1);
    camera.cy = 0.5 * (views.image_height - 1);
  }
  return camera;
}

}  // namespace

const char* toString(CalibrationStatus status) {
  switch (status) {
    case CalibrationStatus::kConverged:
      return "converged";
    case CalibrationStatus::kNotEnoughViews:
      return "not enough views";
    case CalibrationStatus::kDegenerate:
      return "degenerate views";
    case CalibrationStatus::kNoConvergence:
      return "no convergence";
    case CalibrationStatus::kDiverged:
      return "diverged";
  }
  return "unknown";
}

CalibrationResult calibrateCamera(const PlanarViews& views, const CalibrationOptions& options) {
  validate(views);
  if (options.fix_aspect_ratio && !(options.aspect_ratio > 0.0)) {
    throw std::invalid_argument("calibration: the fixed aspect ratio must be positive");
  }
  std::vector<Eigen::Matrix3d> homographies;
  for (size_t view = 0; view < views.image_points.size(); ++view) {
    const HomographyEstimate estimate =
        estimateHomography(views.model_points, views.image_points[view]);
    if (estimate.status != HomographyStatus::kOk) {
      return failure(CalibrationStatus::kDegenerate,
                     fmt::format("view {}: homography: {}", view, toString(estimate.status)));
    }
    homographies.push_back(estimate.H);
  }
  const ClosedFormIntrinsics closed_form = estimateIntrinsicsClosedForm(
      homographies, options.fix_skew, views.image_width, views.image_height);
  if (closed_form.status == ClosedFormStatus::kNotEnoughViews) {
    return failure(CalibrationStatus::kNotEnoughViews,
                   fmt::format("{} views: the closed-form K needs 3 (2 with a fixed zero skew)",
                               views.image_points.size()));
  }
  if (closed_form.status == ClosedFormStatus::kDegenerate) {
    return failure(CalibrationStatus::kDegenerate,
                   "the closed-form K is not determined: the views are degenerate (parallel "
                   "planes, or too few distinct orientations)");
  }
  CalibrationState initial;
  initial.calibration.camera = constrainedCamera(closed_form.K, views, options);
  for (const Eigen::Matrix3d& H : homographies) {
    initial.T_camera_model.push_back(planePoseFromHomography(initial.calibration.camera.K(), H));
  }
  initial.calibration.distortion =
      estimateDistortionLinear(views, initial.calibration.camera, initial.T_camera_model,
                               options.distortion_model)
          .value_or(std::vector<double>(kDistortionCoefficients, 0.0));
  CalibrationResult result =
      resultOf(views, refineCalibration(views, initial, options, RefinementScope::kAllParameters));
  if (result.status == CalibrationStatus::kConverged ||
      result.status == CalibrationStatus::kNoConvergence) {
    result.warnings = degeneracyWarnings(views, result.state.T_camera_model);
  }
  return result;
}

CalibrationResult checkCalibration(const PlanarViews& views, const CameraCalibration& calibration) {
  validate(views);
  const std::vector<double>& distortion = calibration.distortion;
  if (std::any_of(distortion.begin() + std::min<size_t>(distortion.size(), kDistortionCoefficients),
                  distortion.end(), [](double k) { return k != 0.0; })) {
    throw std::invalid_argument(
        "calibration check: the rational distortion terms k4 k5 k6 are not supported");
  }
  CalibrationState initial;
  initial.calibration = calibration;
  initial.calibration.distortion.resize(kDistortionCoefficients, 0.0);
  const Eigen::Matrix3d K = calibration.camera.K();
  const Eigen::Matrix3d K_inverse = K.inverse();
  for (size_t view = 0; view < views.image_points.size(); ++view) {
    std::vector<Eigen::Vector2d> undistorted;
    for (const Eigen::Vector2d& m : views.image_points[view]) {
      const std::optional<Eigen::Vector2d> x =
          undistortNormalised((K_inverse * m.homogeneous()).hnormalized(), calibration.distortion);
      if (!x) {
        return failure(
            CalibrationStatus::kDegenerate,
            fmt::format("view {}: point ({}, {}) cannot be undistorted", view, m.x(), m.y()));
      }
      undistorted.push_back(*x);
    }
    const HomographyEstimate estimate = estimateHomography(views.model_points, undistorted);
    if (estimate.status != HomographyStatus::kOk) {
      return failure(CalibrationStatus::kDegenerate,
                     fmt::format("view {}: homography: {}", view, toString(estimate.status)));
    }
    initial.T_camera_model.push_back(
        planePoseFromHomography(Eigen::Matrix3d::Identity(), estimate.H));
  }
  return resultOf(
      views, refineCalibration(views, initial, CalibrationOptions{}, RefinementScope::kPosesOnly));
}

}  // namespace lineloc
