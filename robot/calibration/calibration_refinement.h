// Maximum-likelihood refinement of a planar calibration, Zhang (ICCV 1999)
// §3.2-3.3, eq. 4:
//
//   min  sum_views sum_points || m_ij - m(K, k, R_i, t_i, M_j) ||^2
//
// over K (fx, fy, cx, cy, skew), the distortion k (k1 k2 [p1 p2 k3]) and
// every plane pose (rotation vector, translation), jointly, by
// Levenberg-Marquardt in Ceres. Fixed parameters (skew, aspect ratio,
// principal point, unused distortion terms) are held by Ceres manifolds.
//
// Uncertainty: at the optimum, Cov = sigma^2 (J^T J)^-1 over the free
// parameters, with sigma^2 = sum ||r||^2 / (2 n - p) the residual variance
// (n points, p free parameters).
#pragma once

#include <string>
#include <vector>

#include "robot/calibration/calibration_problem.h"

namespace lineloc {

enum class RefinementScope {
  kAllParameters,  // intrinsics, distortion and poses (calibration)
  kPosesOnly,      // camera held fixed (checking a calibration on new views)
};

enum class RefinementStatus { kConverged, kNoConvergence, kDiverged };

const char* toString(RefinementStatus status);

struct CalibrationUncertainty {
  bool available = false;
  // Estimated image noise sigma (pixels).
  double noise_sigma_px = 0.0;
  // Standard deviations; zero for fixed parameters.
  Eigen::Matrix<double, 5, 1> intrinsics_std_dev =
      Eigen::Matrix<double, 5, 1>::Zero();  // fx fy cx cy skew
  Eigen::Matrix<double, 5, 1> distortion_std_dev =
      Eigen::Matrix<double, 5, 1>::Zero();  // k1 k2 p1 p2 k3
  // Per view: rotation vector (rad) then translation (m).
  std::vector<Eigen::Matrix<double, 6, 1>> pose_std_dev;
};

struct RefinementResult {
  RefinementStatus status = RefinementStatus::kDiverged;
  CalibrationState state;
  CalibrationUncertainty uncertainty;
  int iterations = 0;
};

// `initial` holds one pose per view (std::invalid_argument otherwise); its
// distortion is read as k1 k2 p1 p2 k3, missing terms zero.
RefinementResult refineCalibration(const PlanarViews& views, const CalibrationState& initial,
                                   const CalibrationOptions& options, RefinementScope scope);

}  // namespace lineloc
