// The data and options of a planar calibration (Zhang, "Flexible Camera
// Calibration by Viewing a Plane from Unknown Orientations", ICCV 1999): views
// of one planar model (Z = 0) and the camera model to fit, K with five
// parameters (fx, fy, cx, cy, skew) and a lens distortion model.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "common/camera/camera_calibration.h"

namespace lineloc {

enum class DistortionModel {
  kRadialK1K2,  // Zhang §3.3: k1 k2 (p1 = p2 = k3 = 0)
  kOpenCv5,     // OpenCV's k1 k2 p1 p2 k3
};

// Coefficients are always kept in OpenCV's five-entry order k1 k2 p1 p2 k3.
inline constexpr int kDistortionCoefficients = 5;

struct CalibrationOptions {
  bool fix_skew = false;
  // fx / fy held at `aspect_ratio`.
  bool fix_aspect_ratio = false;
  double aspect_ratio = 1.0;
  // Principal point held at the image centre ((width - 1) / 2, (height - 1) / 2), as OpenCV does.
  bool fix_principal_point = false;
  DistortionModel distortion_model = DistortionModel::kRadialK1K2;
  int max_iterations = 100;
};

// The model cv::calibrateCamera fits with CALIB_FIX_ASPECT_RATIO from an
// identity start: zero skew, fx = fy, k1 k2 p1 p2 k3.
CalibrationOptions openCvCompatibleOptions();

struct PlanarViews {
  // Model plane points (X, Y) with Z = 0, in metres.
  std::vector<Eigen::Vector2d> model_points;
  // Per view, the measured image points (pixels) of every model point, in order.
  std::vector<std::vector<Eigen::Vector2d>> image_points;
  int image_width = 0;
  int image_height = 0;
};

// A camera and the pose of the model plane in every view.
struct CalibrationState {
  CameraCalibration calibration;
  std::vector<Eigen::Isometry3d> T_camera_model;
};

// Per view, the measured minus the predicted image points (pixels).
std::vector<std::vector<Eigen::Vector2d>> reprojectionResiduals(const PlanarViews& views,
                                                                const CalibrationState& state);

// sqrt(sum ||r||^2 / n) over the given residuals.
double rmsError(const std::vector<Eigen::Vector2d>& residuals);

}  // namespace lineloc
