#include "robot/vision/lines/line_segment.h"

#include <algorithm>

namespace lineloc {
namespace {

Eigen::Matrix2d endpointCovariance(const LineFit& fit, double along, double sigma_along_px) {
  return fit.normalVariance(along) * fit.normal * fit.normal.transpose() +
         sigma_along_px * sigma_along_px * fit.direction * fit.direction.transpose();
}

}  // namespace

int LineSegment::polarity() const {
  // Left of d in an image with y down is (d.y, -d.x) = -normal.
  const double left_gradient = -gradient_sum.dot(fit.normal);
  return left_gradient > 0.0 ? 1 : (left_gradient < 0.0 ? -1 : 0);
}

Eigen::Matrix2d LineSegment::startCovariance() const {
  return endpointCovariance(fit, start_along, start_sigma_along_px);
}

Eigen::Matrix2d LineSegment::endCovariance() const {
  return endpointCovariance(fit, end_along, end_sigma_along_px);
}

void LineSegment::setExtent(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const double ta = fit.along(a);
  const double tb = fit.along(b);
  start_along = std::min(ta, tb);
  end_along = std::max(ta, tb);
}

}  // namespace lineloc
