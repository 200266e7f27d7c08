#include "robot/vision/edges/undistortion_table.h"

#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <optional>
#include <stdexcept>

#include "common/camera/lens_distortion.h"

namespace lineloc {
namespace {

bool hasDistortion(const std::vector<double>& coefficients) {
  return std::any_of(coefficients.begin(), coefficients.end(), [](double k) { return k != 0.0; });
}

}  // namespace

UndistortionTable::UndistortionTable(const CameraCalibration& calibration)
    : width_(calibration.camera.width), height_(calibration.camera.height) {
  if (calibration.lens == LensModel::kEquidistant && width_ >= 2 && height_ >= 2) {
    fillEquidistant(calibration);
    return;
  }
  if (!hasDistortion(calibration.distortion) || width_ < 2 || height_ < 2) {
    return;
  }
  std::vector<cv::Point2f> pixels;
  pixels.reserve(static_cast<size_t>(width_) * height_);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      pixels.emplace_back(static_cast<float>(x), static_cast<float>(y));
    }
  }
  cv::Mat K;
  cv::eigen2cv(calibration.camera.K(), K);
  std::vector<cv::Point2f> undistorted;
  cv::undistortPoints(pixels, undistorted, K, calibration.distortion, cv::noArray(), K,
                      cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-9));
  table_.reserve(undistorted.size());
  for (const cv::Point2f& u : undistorted) {
    if (!std::isfinite(u.x) || !std::isfinite(u.y)) {
      const size_t at = table_.size();
      throw std::invalid_argument(
          fmt::format("calibration: the distortion model cannot be inverted at pixel ({}, {})",
                      at % width_, at / width_));
    }
    table_.emplace_back(u.x, u.y);
  }
}

void UndistortionTable::fillEquidistant(const CameraCalibration& calibration) {
  const Eigen::Matrix3d K = calibration.camera.K();
  const Eigen::Matrix3d K_inverse = K.inverse();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  table_.reserve(static_cast<size_t>(width_) * height_);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const Eigen::Vector3d normalised = K_inverse * Eigen::Vector3d(x, y, 1.0);
      const std::optional<Eigen::Vector3d> ray =
          undistortEquidistant(normalised.head<2>(), calibration.distortion);
      if (!ray || !(ray->z() > 0.0)) {
        table_.emplace_back(nan, nan);
        continue;
      }
      const Eigen::Vector3d u = K * (*ray / ray->z());
      const bool inside =
          u.x() >= 0.0 && u.x() <= width_ - 1 && u.y() >= 0.0 && u.y() <= height_ - 1;
      table_.push_back(inside
                           ? Eigen::Vector2f(static_cast<float>(u.x()), static_cast<float>(u.y()))
                           : Eigen::Vector2f(nan, nan));
    }
  }
}

UndistortionTable::Cell UndistortionTable::cellOf(const Eigen::Vector2f& p) const {
  const int x0 = std::clamp(static_cast<int>(std::floor(p.x())), 0, width_ - 2);
  const int y0 = std::clamp(static_cast<int>(std::floor(p.y())), 0, height_ - 2);
  return {x0, y0, p.x() - static_cast<float>(x0), p.y() - static_cast<float>(y0)};
}

Eigen::Vector2f UndistortionTable::undistort(const Eigen::Vector2f& distorted) const {
  if (isIdentity()) {
    return distorted;
  }
  const Cell c = cellOf(distorted);
  const Eigen::Vector2f top = (1.0f - c.ax) * at(c.x0, c.y0) + c.ax * at(c.x0 + 1, c.y0);
  const Eigen::Vector2f bottom = (1.0f - c.ax) * at(c.x0, c.y0 + 1) + c.ax * at(c.x0 + 1, c.y0 + 1);
  return (1.0f - c.ay) * top + c.ay * bottom;
}

Eigen::Matrix2f UndistortionTable::jacobian(const Eigen::Vector2f& distorted) const {
  if (isIdentity()) {
    return Eigen::Matrix2f::Identity();
  }
  const Cell c = cellOf(distorted);
  Eigen::Matrix2f J;
  J.col(0) = (1.0f - c.ay) * (at(c.x0 + 1, c.y0) - at(c.x0, c.y0)) +
             c.ay * (at(c.x0 + 1, c.y0 + 1) - at(c.x0, c.y0 + 1));
  J.col(1) = (1.0f - c.ax) * (at(c.x0, c.y0 + 1) - at(c.x0, c.y0)) +
             c.ax * (at(c.x0 + 1, c.y0 + 1) - at(c.x0 + 1, c.y0));
  return J;
}

}  // namespace lineloc
