#include "robot/vision/lines/line_moments.h"

#include <algorithm>
#include <cmath>

namespace lineloc {

PointMoments& PointMoments::operator+=(const PointMoments& other) {
  n += other.n;
  sx += other.sx;
  sy += other.sy;
  sxx += other.sxx;
  sxy += other.sxy;
  syy += other.syy;
  return *this;
}

PointMoments PointMoments::operator-(const PointMoments& other) const {
  return {n - other.n,     sx - other.sx,   sy - other.sy,
          sxx - other.sxx, sxy - other.sxy, syy - other.syy};
}

void cumulativeMoments(std::span<const Eigen::Vector2f> points, std::vector<PointMoments>& prefix) {
  prefix.resize(points.size() + 1);
  PointMoments running;
  prefix[0] = running;
  for (size_t i = 0; i < points.size(); ++i) {
    running.add(points[i]);
    prefix[i + 1] = running;
  }
}

LineFit fitLine(const PointMoments& moments, const LineFitOptions& options) {
  LineFit fit;
  if (moments.n < 3.0) {
    return fit;
  }
  const double n = moments.n;
  fit.centroid = {moments.sx / n, moments.sy / n};
  const double a = moments.sxx / n - fit.centroid.x() * fit.centroid.x();
  const double b = moments.sxy / n - fit.centroid.x() * fit.centroid.y();
  const double c = moments.syy / n - fit.centroid.y() * fit.centroid.y();
  const double half_trace = 0.5 * (a + c);
  const double half_difference = 0.5 * (a - c);
  const double radius = std::sqrt(half_difference * half_difference + b * b);
  const double lambda_max = half_trace + radius;
  const double lambda_min = std::max(0.0, half_trace - radius);
  if (!(lambda_max > 0.0)) {
    fit.status = LineFitStatus::kDegenerate;
    return fit;
  }
  // Major eigenvector of [a b; b c] from the larger row of S - lambda_max I
  // (zero only for an isotropic scatter, whose axis is arbitrary).
  const Eigen::Vector2d major =
      a >= c ? Eigen::Vector2d(lambda_max - c, b) : Eigen::Vector2d(b, lambda_max - a);
  fit.direction = major.squaredNorm() > 0.0 ? major.normalized() : Eigen::Vector2d::UnitX();
  if (fit.direction.y() < 0.0 || (fit.direction.y() == 0.0 && fit.direction.x() < 0.0)) {
    fit.direction = -fit.direction;
  }
  fit.normal = {-fit.direction.y(), fit.direction.x()};
  fit.residual_sigma_px =
      std::max(options.min_sigma_px, std::sqrt(n * lambda_min / std::max(1.0, n - 2.0)));
  const double effective_n = std::max(1.0, n / options.points_per_sample);
  fit.sigma_offset_px = fit.residual_sigma_px / std::sqrt(effective_n);
  fit.sigma_angle_rad = fit.residual_sigma_px / std::sqrt(effective_n * lambda_max);
  fit.status = LineFitStatus::kOk;
  return fit;
}

}  // namespace lineloc
