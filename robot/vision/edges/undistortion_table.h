// Distorted -> undistorted pixel lookup table, built once from a calibration.
//
// Lines are straight only in the undistorted image (Persa & Jonker §2.1, §3),
// so edge points and corners are moved into undistorted pixel coordinates
// before any line is fitted. The table holds u(p), the undistorted position of
// every distorted pixel centre p (OpenCV's iterative inverse of the
// k1 k2 p1 p2 [k3..k6] model, projected again with the same K), and is read
// by bilinear interpolation, which is exact to second order in the pixel
// spacing: the error is below 1/8 of the model's second derivative times px^2.
//
// A fisheye's (equidistant, lens_distortion.h) u(p) is its ray projected by
// the same K; where that falls outside the image, or the ray is 90 degrees
// or more off the axis, u(p) is not finite (NaN): the point is not in the
// undistorted view (camera_calibration.h).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "common/camera/camera_calibration.h"

namespace lineloc {

class UndistortionTable {
 public:
  // Throws std::invalid_argument naming the pixel where the model has no
  // finite inverse.
  explicit UndistortionTable(const CameraCalibration& calibration);

  // True when the calibration has no distortion: u(p) = p.
  bool isIdentity() const { return table_.empty(); }

  // u(p) for a distorted pixel position p (bilinear in the table; positions
  // outside the image are extrapolated linearly from the border cells); NaN
  // next to a fisheye's pixel outside the undistorted view.
  Eigen::Vector2f undistort(const Eigen::Vector2f& distorted) const;

  // J = du/dp at p, to carry a covariance across: Sigma_u = J Sigma_p J^T.
  Eigen::Matrix2f jacobian(const Eigen::Vector2f& distorted) const;

 private:
  struct Cell {
    int x0, y0;
    float ax, ay;
  };
  void fillEquidistant(const CameraCalibration& calibration);
  Cell cellOf(const Eigen::Vector2f& p) const;
  const Eigen::Vector2f& at(int x, int y) const { return table_[y * width_ + x]; }

  int width_;
  int height_;
  std::vector<Eigen::Vector2f> table_;
};

}  // namespace lineloc
