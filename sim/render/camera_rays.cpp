#include "sim/render/camera_rays.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "common/camera/lens_distortion.h"

namespace lineloc {
CameraRays::CameraRays(const CameraCalibration& calibration)
    : width_(calibration.camera.width), height_(calibration.camera.height) {
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
      const std::optional<Eigen::Vector2d> undistorted =
          undistortNormalised({x_d, y_d}, calibration.distortion);
      if (!undistorted) {
        ++invalid_count_;
        continue;
      }
      directions_[v * width_ + u] =
          Eigen::Vector3d(undistorted->x(), undistorted->y(), 1.0).normalized().cast<float>();
    }
  }
}

}  // namespace lineloc
