// Lens distortion in OpenCV's model (Brown-Conrady radial and tangential terms
// with the optional rational radial factor), on normalised image coordinates
// x = X/Z, y = Y/Z:
//
//   r^2 = x^2 + y^2
//   radial = (1 + k1 r^2 + k2 r^4 + k3 r^6) / (1 + k4 r^2 + k5 r^4 + k6 r^6)
//   x_d = x radial + 2 p1 x y + p2 (r^2 + 2 x^2)
//   y_d = y radial + p1 (r^2 + 2 y^2) + 2 p2 x y
//
// Coefficients are in OpenCV's order k1 k2 p1 p2 [k3 [k4 k5 k6]]; missing ones
// are zero, so Zhang's radial model (eq. 3 of §3.3) is {k1, k2}.
//
// A fisheye lens in the equidistant model (Kannala & Brandt, "A generic
// camera model and calibration method for conventional, wide-angle, and
// fish-eye lenses", PAMI 28(8), 2006, eq. 6; OpenCV's cv::fisheye, Kalibr's
// pinhole-equi) maps a ray at angle theta from the axis, in the direction
// (X, Y)/|(X, Y)|, to the normalised radius
//
//   theta_d = theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6 + k4 theta^8)
//
// so that rays beyond 90 degrees have an image too.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace lineloc {

// Templated so that automatic differentiation (ceres::Jet) can run through it.
// `coefficients` points to `count` values (0 to 8).
template <typename T>
Eigen::Matrix<T, 2, 1> distortNormalised(const Eigen::Matrix<T, 2, 1>& undistorted,
                                         const T* coefficients, int count) {
  const auto k = [&](int i) { return i < count ? coefficients[i] : T(0.0); };
  const T& x = undistorted.x();
  const T& y = undistorted.y();
  const T r2 = x * x + y * y;
  const T r4 = r2 * r2;
  const T r6 = r4 * r2;
  const T radial =
      (T(1.0) + k(0) * r2 + k(1) * r4 + k(4) * r6) / (T(1.0) + k(5) * r2 + k(6) * r4 + k(7) * r6);
  const T two_xy = T(2.0) * x * y;
  return {x * radial + k(2) * two_xy + k(3) * (r2 + T(2.0) * x * x),
          y * radial + k(2) * (r2 + T(2.0) * y * y) + k(3) * two_xy};
}

Eigen::Vector2d distortNormalised(const Eigen::Vector2d& undistorted,
                                  const std::vector<double>& coefficients);

// Inverts distortNormalised by Gauss-Newton iteration from x = x_d. Returns
// nothing when it does not reach a round-trip error below 1e-12 (the point lies
// outside the region where the model is invertible).
std::optional<Eigen::Vector2d> undistortNormalised(const Eigen::Vector2d& distorted,
                                                   const std::vector<double>& coefficients);

// The fisheye's normalised image point (x_d, y_d) = theta_d (X, Y)/|(X, Y)| of
// the ray `ray` (any length, not along -Z); coefficients k1 k2 k3 k4.
Eigen::Vector2d distortEquidistant(const Eigen::Vector3d& ray,
                                   const std::vector<double>& coefficients);

// The unit ray of a fisheye's normalised image point, theta found from
// theta_d by Newton's method; nothing where theta_d is not reached by a theta
// in [0, pi) on which the model increases.
std::optional<Eigen::Vector3d> undistortEquidistant(const Eigen::Vector2d& distorted,
                                                    const std::vector<double>& coefficients);

}  // namespace lineloc
