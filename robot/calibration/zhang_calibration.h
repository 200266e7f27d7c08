// Camera calibration from views of a planar pattern, the method of Zhang,
// "Flexible Camera Calibration by Viewing a Plane from Unknown Orientations"
// (ICCV 1999), used by Persa & Jonker §2.1:
//
//  1. per view, the plane-to-image homography (common/homography, eq. 1-2);
//  2. K in closed form from V b = 0 (eq. 3, closed_form_intrinsics.h);
//  3. each view's plane pose from its homography (planar_extrinsics.h);
//  4. the distortion by linear least squares (eq. 5-6, distortion_initialisation.h);
//  5. the joint maximum-likelihood estimate of everything (eq. 4,
//     calibration_refinement.h), with standard deviations.
//
// The result names the views that make the problem near-degenerate: fewer
// than three views, nearly parallel planes, or patterns covering a small part
// of the image.
#pragma once

#include <string>
#include <vector>

#include "robot/calibration/calibration_problem.h"
#include "robot/calibration/calibration_refinement.h"

namespace lineloc {

enum class CalibrationStatus {
  kConverged,
  kNotEnoughViews,  // fewer than 3 views (2 with a fixed zero skew)
  kDegenerate,      // a view's homography or the closed-form K cannot be computed
  kNoConvergence,   // the refinement hit its iteration limit; the result is its last iterate
  kDiverged,        // the refinement failed; no result
};

const char* toString(CalibrationStatus status);

struct CalibrationResult {
  CalibrationStatus status = CalibrationStatus::kNotEnoughViews;
  // Why the status is not kConverged, naming the view when one is to blame.
  std::string message;
  CalibrationState state;
  CalibrationUncertainty uncertainty;
  double rms_error_px = 0.0;
  std::vector<double> per_view_rms_error_px;
  std::vector<std::vector<Eigen::Vector2d>> residuals_px;
  std::vector<std::string> warnings;
};

// Throws std::invalid_argument when the views are malformed (a view's point
// count differs from the model's, non-finite coordinates, no image size).
CalibrationResult calibrateCamera(const PlanarViews& views, const CalibrationOptions& options);

// The reprojection error of an existing calibration on new views: the plane
// poses are estimated (homography, then maximum likelihood) with the camera held fixed.
// Throws std::invalid_argument as calibrateCamera does, and for a calibration
// with rational distortion terms (k4 k5 k6).
CalibrationResult checkCalibration(const PlanarViews& views, const CameraCalibration& calibration);

}  // namespace lineloc
