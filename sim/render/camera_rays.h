// The ray through every pixel of a calibrated camera with lens distortion, for
// rendering by inverse mapping: pixel (u, v) of the distorted image sees the
// direction (x, y, 1) whose OpenCV distortion lands on that pixel,
//   r^2 = x^2 + y^2,
//   s = (1 + k1 r^2 + k2 r^4 + k3 r^6) / (1 + k4 r^2 + k5 r^4 + k6 r^6),
//   x_d = x s + 2 p1 x y + p2 (r^2 + 2 x^2),
//   y_d = y s + p1 (r^2 + 2 y^2) + 2 p2 x y,
//   u = fx x_d + skew y_d + cx,  v = fy y_d + cy
// (the model of cv::projectPoints, common/camera/lens_distortion.h; Zhang's
// radial k1 k2 of Persa & Jonker §2.1 is the case p = k3..k6 = 0); for a
// fisheye, the ray whose equidistant image (lens_distortion.h) is the pixel,
// up to and beyond 90 degrees off the axis. The inverses have no closed
// form: each pixel is solved iteratively, once per camera.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "common/camera/camera_calibration.h"

namespace lineloc {

// Unit ray directions in the camera frame (OpenCV: x right, y down, z forward),
// one per pixel centre, row-major. A pixel the model cannot invert gets a zero
// direction and is rendered black.
class CameraRays {
 public:
  explicit CameraRays(const CameraCalibration& calibration);

  int width() const { return width_; }
  LensModel lens() const { return lens_; }
  int height() const { return height_; }
  const Eigen::Vector3f& direction(int u, int v) const { return directions_[v * width_ + u]; }
  // Unit direction through the sub-pixel point (u, v): bilinear between the
  // four nearest pixel centres' directions (extrapolated beyond the outermost
  // ones), normalised. The lens map bends by under 1e-3 px across a pixel, so
  // this is as exact as direction() for rendering. Zero where one of the four
  // has no ray.
  Eigen::Vector3f directionAt(float u, float v) const;
  // Pixels with no valid ray (zero direction).
  int invalidCount() const { return invalid_count_; }

 private:
  LensModel lens_ = LensModel::kRadialTangential;
  int width_ = 0;
  int height_ = 0;
  int invalid_count_ = 0;
  std::vector<Eigen::Vector3f> directions_;
};

}  // namespace lineloc
