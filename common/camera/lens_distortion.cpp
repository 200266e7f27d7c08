#include "common/camera/lens_distortion.h"

#include <ceres/jet.h>

#include <Eigen/LU>
#include <cmath>
#include <utility>

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

namespace {

// theta_d(theta) and its derivative.
std::pair<double, double> equidistantRadius(double theta, const std::vector<double>& k) {
  const auto coefficient = [&](size_t i) { return i < k.size() ? k[i] : 0.0; };
  const double t2 = theta * theta;
  const double polynomial =
      1.0 +
      t2 * (coefficient(0) + t2 * (coefficient(1) + t2 * (coefficient(2) + t2 * coefficient(3))));
  const double derivative =
      1.0 +
      t2 * (3.0 * coefficient(0) +
            t2 * (5.0 * coefficient(1) + t2 * (7.0 * coefficient(2) + t2 * 9.0 * coefficient(3))));
  return {theta * polynomial, derivative};
}

}  // namespace

Eigen::Vector2d distortEquidistant(const Eigen::Vector3d& ray,
                                   const std::vector<double>& coefficients) {
  const double radial = ray.head<2>().norm();
  if (radial == 0.0) {
    return Eigen::Vector2d::Zero();
  }
  const double theta = std::atan2(radial, ray.z());
  return equidistantRadius(theta, coefficients).first * ray.head<2>() / radial;
}

std::optional<Eigen::Vector3d> undistortEquidistant(const Eigen::Vector2d& distorted,
                                                    const std::vector<double>& coefficients) {
  const double theta_d = distorted.norm();
  if (theta_d == 0.0) {
    return Eigen::Vector3d::UnitZ();
  }
  double theta = theta_d;
  for (int iteration = 0; iteration < kMaxUndistortIterations; ++iteration) {
    const auto [value, derivative] = equidistantRadius(theta, coefficients);
    if (!(derivative > 0.0) || !std::isfinite(value)) {
      return std::nullopt;
    }
    const double step = (value - theta_d) / derivative;
    theta -= step;
    if (std::abs(step) < kRoundTripTolerance) {
      if (!(theta >= 0.0 && theta < M_PI)) {
        return std::nullopt;
      }
      const Eigen::Vector2d direction = distorted / theta_d;
      return Eigen::Vector3d(std::sin(theta) * direction.x(), std::sin(theta) * direction.y(),
                             std::cos(theta));
    }
  }
  return std::nullopt;
}

}  // namespace lineloc
