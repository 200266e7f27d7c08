#include "sim/render/camera_rays.h"

#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lineloc {
namespace {

constexpr int kMaxGaussNewtonIterations = 50;

}  // namespace

LensDistortion::LensDistortion(const std::vector<double>& coefficients) {
  if (coefficients.size() > k_.size()) {
    throw std::invalid_argument(
        fmt::format("LensDistortion: {} coefficients given, at most 8 (k1 k2 p1 p2 k3 k4 k5 k6)",
                    coefficients.size()));
  }
  std::copy(coefficients.begin(), coefficients.end(), k_.begin());
}

Eigen::Vector2d LensDistortion::distort(const Eigen::Vector2d& undistorted) const {
  const double x = undistorted.x();
  const double y = undistorted.y();
  const double r2 = x * x + y * y;
  const double radial = (1.0 + r2 * (k_[0] + r2 * (k_[1] + r2 * k_[4]))) /
                        (1.0 + r2 * (k_[5] + r2 * (k_[6] + r2 * k_[7])));
  return {x * radial + 2.0 * k_[2] * x * y + k_[3] * (r2 + 2.0 * x * x),
          y * radial + k_[2] * (r2 + 2.0 * y * y) + 2.0 * k_[3] * x * y};
}

// d(x_d, y_d)/d(x, y) by differentiating the model above.
Eigen::Matrix2d LensDistortion::jacobian(const Eigen::Vector2d& undistorted) const {
  const double x = undistorted.x();
  const double y = undistorted.y();
  const double r2 = x * x + y * y;
  const double numerator = 1.0 + r2 * (k_[0] + r2 * (k_[1] + r2 * k_[4]));
  const double denominator = 1.0 + r2 * (k_[5] + r2 * (k_[6] + r2 * k_[7]));
  const double d_numerator = k_[0] + r2 * (2.0 * k_[1] + 3.0 * r2 * k_[4]);
  const double d_denominator = k_[5] + r2 * (2.0 * k_[6] + 3.0 * r2 * k_[7]);
  const double radial = numerator / denominator;
  // d radial / d r2, then d r2 / dx = 2x.
  const double d_radial =
      (d_numerator * denominator - numerator * d_denominator) / (denominator * denominator);
  Eigen::Matrix2d J;
  J(0, 0) = radial + 2.0 * x * x * d_radial + 2.0 * k_[2] * y + 6.0 * k_[3] * x;
  J(0, 1) = 2.0 * x * y * d_radial + 2.0 * k_[2] * x + 2.0 * k_[3] * y;
  J(1, 0) = 2.0 * x * y * d_radial + 2.0 * k_[2] * x + 2.0 * k_[3] * y;
  J(1, 1) = radial + 2.0 * y * y * d_radial + 6.0 * k_[2] * y + 2.0 * k_[3] * x;
  return J;
}

bool LensDistortion::undistort(const Eigen::Vector2d& distorted, Eigen::Vector2d& undistorted,
                               double tolerance) const {
  Eigen::Vector2d x = distorted;
  for (int iteration = 0; iteration < kMaxGaussNewtonIterations; ++iteration) {
    const Eigen::Vector2d residual = distort(x) - distorted;
    if (residual.norm() <= tolerance) {
      undistorted = x;
      return true;
    }
    const Eigen::Matrix2d J = jacobian(x);
    if (!(std::abs(J.determinant()) > 1e-12)) {
      return false;
    }
    x -= J.inverse() * residual;
    if (!x.allFinite()) {
      return false;
    }
  }
  return false;
}

CameraRays::CameraRays(const CameraCalibration& calibration)
    : width_(calibration.camera.width), height_(calibration.camera.height) {
  const PinholeCamera& camera = calibration.camera;
  if (width_ <= 0 || height_ <= 0 || !(camera.fx > 0.0) || !(camera.fy > 0.0)) {
    throw std::invalid_argument(fmt::format("CameraRays: invalid camera {}x{} fx {} fy {}", width_,
                                            height_, camera.fx, camera.fy));
  }
  const LensDistortion lens(calibration.distortion);
  directions_.resize(static_cast<size_t>(width_) * height_, Eigen::Vector3f::Zero());
  // Tolerance 1e-12 in normalised coordinates is ~1e-9 px: exact for rendering.
  for (int v = 0; v < height_; ++v) {
    const double y_d = (v - camera.cy) / camera.fy;
    for (int u = 0; u < width_; ++u) {
      const double x_d = (u - camera.cx - camera.skew * y_d) / camera.fx;
      Eigen::Vector2d undistorted;
      if (!lens.undistort({x_d, y_d}, undistorted)) {
        ++invalid_count_;
        continue;
      }
      directions_[v * width_ + u] =
          Eigen::Vector3d(undistorted.x(), undistorted.y(), 1.0).normalized().cast<float>();
    }
  }
}

}  // namespace lineloc
