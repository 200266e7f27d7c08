// Linear least-squares estimate of the lens distortion with K and the plane
// poses held fixed, Zhang (ICCV 1999) §3.3, eq. 5-6, extended to OpenCV's
// tangential and third radial terms.
//
// For each model point, (x, y) are its ideal normalised coordinates, (u, v) its
// ideal pixel and (u_d, v_d) the measured one. The distortion is linear in the
// coefficients k = [k1 k2 p1 p2 k3]:
//
//   dx = x (k1 r^2 + k2 r^4 + k3 r^6) + 2 p1 x y + p2 (r^2 + 2 x^2)
//   dy = y (k1 r^2 + k2 r^4 + k3 r^6) + p1 (r^2 + 2 y^2) + 2 p2 x y
//   u_d - u = fx dx + skew dy,   v_d - v = fy dy                   (D k = d)
//
// With only k1 k2 these rows are Zhang's eq. 5, and k = (D^T D)^-1 D^T d is
// eq. 6.
#pragma once

#include <optional>
#include <vector>

#include "robot/calibration/calibration_problem.h"

namespace lineloc {

// Returns k1 k2 p1 p2 k3 (the terms the model leaves out are zero), or nothing
// when the points do not determine them (e.g. all of them at the image centre).
std::optional<std::vector<double>> estimateDistortionLinear(
    const PlanarViews& views, const PinholeCamera& camera,
    const std::vector<Eigen::Isometry3d>& T_camera_model, DistortionModel model);

}  // namespace lineloc
