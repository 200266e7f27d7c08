#include "sim/render/camera_rays.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/camera/lens_distortion.h"

namespace lineloc {
namespace {

// The ray of a distorted normalised point, for the calibration's lens.
std::optional<Eigen::Vector3d> rayOf(const Eigen::Vector2d& distorted,
                                     const CameraCalibration& calibration) {
  if (calibration.lens == LensModel::kEquidistant) {
    return undistortEquidistant(distorted, calibration.distortion);
  }
  const std::optional<Eigen::Vector2d> undistorted =
      undistortNormalised(distorted, calibration.distortion);
  if (!undistorted) {
    return std::nullopt;
  }
  return Eigen::Vector3d(undistorted->x(), undistorted->y(), 1.0);
}

}  // namespace

CameraRays::CameraRays(const CameraCalibration& calibration)
    : lens_(calibration.lens),
      width_(calibration.camera.width),
      height_(calibration.camera.height) {
  const PinholeCamera& camera = calibration.camera;
  if (width_ <= 0 || height_ <= 0 || !(camera.fx > 0.0) || !(camera.fy > 0.0)) {
    throw std::invalid_argument(fmt::format("CameraRays: invalid camera {}x{} fx {} fy {}", width_,
                                            height_, camera.fx, camera.fy));
  }
  directions_.resize(static_cast<size_t>(width_) * height_, Eigen::Vector3f::Zero());
  // Round trip below 1e-12 in normalised coordinates, ~1e-9 px: exact for rendering.
  for (int v = 0; v < height_; ++v) {
    const double y_d = (v - camera.cy) / camera.fy;
    for (int u = 0; u < width_; ++u) {
      const double x_d = (u - camera.cx - camera.skew * y_d) / camera.fx;
      const std::optional<Eigen::Vector3d> ray = rayOf({x_d, y_d}, calibration);
      if (!ray) {
        ++invalid_count_;
        continue;
      }
      directions_[v * width_ + u] = ray->normalized().cast<float>();
    }
  }
}

Eigen::Vector3f CameraRays::directionAt(float u, float v) const {
  // The cell's top-left pixel centre, kept inside the image so that points in
  // the outermost half pixel extrapolate from the last two centres.
  const int u0 = std::clamp(static_cast<int>(std::floor(u)), 0, std::max(width_ - 2, 0));
  const int v0 = std::clamp(static_cast<int>(std::floor(v)), 0, std::max(height_ - 2, 0));
  const int u1 = std::min(u0 + 1, width_ - 1);
  const int v1 = std::min(v0 + 1, height_ - 1);
  const Eigen::Vector3f& d00 = direction(u0, v0);
  const Eigen::Vector3f& d10 = direction(u1, v0);
  const Eigen::Vector3f& d01 = direction(u0, v1);
  const Eigen::Vector3f& d11 = direction(u1, v1);
  if (d00.isZero() || d10.isZero() || d01.isZero() || d11.isZero()) {
    return Eigen::Vector3f::Zero();
  }
  const float a = u - static_cast<float>(u0);
  const float b = v - static_cast<float>(v0);
  return ((1.0f - b) * ((1.0f - a) * d00 + a * d10) + b * ((1.0f - a) * d01 + a * d11))
      .normalized();
}

}  // namespace lineloc
