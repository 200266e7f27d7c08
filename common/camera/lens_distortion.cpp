#include "common/camera/lens_distortion.h"

#include <ceres/jet.h>

#include <Eigen/LU>

namespace lineloc {

namespace {

constexpr int kMaxUndistortIterations = 20;
constexpr double kRoundTripTolerance = 1e-12;

}  // namespace

Eigen::Vector2d distortNormalised(const Eigen::Vector2d& undistorted,
                                  const std::vector<double>& coefficients) {
  return distortNormalised<double>(undistorted, coefficients.data(),
                                   static_cast<int>(coefficients.size()));
}

std::optional<Eigen::Vector2d> undistortNormalised(const Eigen::Vector2d& distorted,
                                                   const std::vector<double>& coefficients) {
  using Jet = ceres::Jet<double, 2>;
  std::vector<Jet> jet_coefficients(coefficients.begin(), coefficients.end());
  const int count = static_cast<int>(coefficients.size());
  Eigen::Vector2d x = distorted;
  for (int iteration = 0; iteration < kMaxUndistortIterations; ++iteration) {
    const Eigen::Matrix<Jet, 2, 1> x_jet(Jet(x.x(), 0), Jet(x.y(), 1));
    const Eigen::Matrix<Jet, 2, 1> f =
        distortNormalised<Jet>(x_jet, jet_coefficients.data(), count);
    const Eigen::Vector2d residual(f.x().a - distorted.x(), f.y().a - distorted.y());
    if (!residual.allFinite()) {
      return std::nullopt;
    }
    if (residual.norm() < kRoundTripTolerance) {
      return x;
    }
    Eigen::Matrix2d J;
    J << f.x().v.transpose(), f.y().v.transpose();
    x -= J.partialPivLu().solve(residual);
  }
  return std::nullopt;
}

}  // namespace lineloc
