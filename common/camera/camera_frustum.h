// The view frustum of a pinhole camera, as six half-spaces n . x + d >= 0 in
// the camera frame (OpenCV: x right, y down, z forward), and Cyrus-Beck
// clipping of segments against half-spaces (Cyrus & Beck, "Generalized two-
// and three-dimensional clipping", Computers & Graphics 1978).
//
// The side planes pass through the optical centre and the rays of two
// adjacent image corners r(u, v) = K^-1 [u v 1]^T (the image grown by a
// margin), with normal r_i x r_(i+1) turned towards the centre ray; near and
// far are z >= near and z <= far.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>

#include "common/camera/camera_calibration.h"

namespace lineloc {

// (n, d): a point x is inside when n . x + d >= 0.
using HalfSpaces = std::array<Eigen::Vector4d, 6>;

// The frustum of `camera` between depths near_m and far_m, its image grown by
// margin_px on every side; camera frame.
HalfSpaces cameraFrustum(const PinholeCamera& camera, double near_m, double far_m,
                         double margin_px = 0.0);

// The rays K^-1 [u v 1]^T of the corners of the image grown by margin_px,
// in order (0, 0), (w, 0), (w, h), (0, h); camera frame, depth 1.
std::array<Eigen::Vector3d, 4> imageCornerRays(const PinholeCamera& camera, double margin_px);

// The parameter interval [s_enter, s_leave] of a + s (b - a), s in [0, 1],
// inside every half-space; nullopt when it is empty. On the plane's function
// f(s) = f(a) + s (f(b) - f(a)) the boundary is at s = f(a) / (f(a) - f(b)).
std::optional<std::array<double, 2>> clipSegment(const HalfSpaces& planes, const Eigen::Vector3d& a,
                                                 const Eigen::Vector3d& b);

}  // namespace lineloc
