// The inputs and the result of camera pose estimation from point and line
// correspondences (Persa & Jonker, "Real-Time Computer Vision System for Mobile
// Robot", §2.2): 3D model points and segments in the world frame matched with
// undistorted image points and segments of a calibrated pinhole camera.
//
// The estimated pose is T_world_camera (camera OpenCV frame: x right, y down,
// z forward). Its covariance follows common/geometry/pose.h: e = [dp; dtheta]
// in the world frame, t = t_est + dp, R = Exp(dtheta) R_est.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "common/camera/camera_calibration.h"
#include "common/geometry/pose.h"

namespace lineloc {

// A 3D model point and its measured image point (undistorted pixels) with the
// measurement's 2x2 covariance in pixels^2.
struct PointCorrespondence {
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
};

// A 3D model segment and the measured image segment (undistorted pixels) of
// the same line, with per-endpoint 2x2 covariances in pixels^2 (the fields of
// ImageSegment in common/messages/messages.h). Endpoints need not correspond:
// only the measured line's position matters, the model segment's endpoints
// must lie on it.
struct LineCorrespondence {
  Eigen::Vector3d start_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_world = Eigen::Vector3d::Zero();
  Eigen::Vector2d start_pixel = Eigen::Vector2d::Zero();
  Eigen::Vector2d end_pixel = Eigen::Vector2d::Zero();
  Eigen::Matrix2d start_covariance = Eigen::Matrix2d::Identity();
  Eigen::Matrix2d end_covariance = Eigen::Matrix2d::Identity();
};

struct PoseProblem {
  PinholeCamera camera;
  std::vector<PointCorrespondence> points;
  std::vector<LineCorrespondence> lines;
};

enum class PoseStatus {
  kConverged,
  kInvalidInput,              // non-finite or out-of-range numbers, bad covariance
  kNotEnoughCorrespondences,  // too few constraints for the requested start
  kDegenerate,                // collinear points, parallel or concurrent lines, rank loss
  kAmbiguous,                 // two poses explain the data equally well (planar flip)
  kBehindCamera,              // a model point or endpoint is not in front of the camera
  kDiverged,                  // non-finite step or absurd pose during refinement
  kIterationLimit,            // stopped by the iteration count before converging
  kInconsistent,              // residuals far beyond the stated measurement noise
};

const char* toString(PoseStatus status);

// Residual of one correspondence at the estimated pose: residual_px is the
// image distance (points) or the root sum of squares of both projected model
// endpoints' distances to the measured line (lines); normalized_residual is
// the same in units of its standard deviation; weight is the robust loss's
// derivative rho'(normalized_residual^2) used in the final iteration.
struct CorrespondenceResidual {
  double residual_px = 0.0;
  double normalized_residual = 0.0;
  double weight = 1.0;
};

struct PoseEstimate {
  PoseStatus status = PoseStatus::kInvalidInput;
  // What failed and where (e.g. "point 3: pixel is not finite"); empty on success.
  std::string message;
  // Camera pose and the covariance of e = [dp; dtheta] (common/geometry/pose.h),
  // propagated from the measurement covariances: (J^T W J)^-1.
  PoseWithCovariance T_world_camera;
  // RMS over all scalar residuals (two per point, two per line), in pixels.
  double rms_residual_px = 0.0;
  std::vector<CorrespondenceResidual> point_residuals;
  std::vector<CorrespondenceResidual> line_residuals;
  int iterations = 0;
  // Half the sum of the robust loss over all normalized residuals.
  double cost = 0.0;
  // With kAmbiguous (and whenever a second planar candidate converged): the
  // other pose and its RMS residual in pixels.
  std::optional<Eigen::Isometry3d> alternative_T_world_camera;
  double alternative_rms_residual_px = 0.0;

  bool ok() const { return status == PoseStatus::kConverged; }
};

// An estimate carrying only a failure status and its message.
PoseEstimate poseFailure(PoseStatus status, std::string message);

}  // namespace lineloc
