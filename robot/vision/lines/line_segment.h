// A straight image segment fitted to edge points, with the evidence it was
// fitted from (so segments can merge) and its uncertainty.
//
// The endpoints lie on the fitted line at along-coordinates start_along <
// end_along from the centroid. Endpoint covariance, with n the line normal and
// d its direction (Persa & Jonker §3 send each line with its uncertainty):
//   Sigma = (sigma_offset^2 + t^2 sigma_angle^2) n n^T + sigma_along^2 d d^T,
// t the endpoint's along-coordinate. These are the exact marginals of the
// fit; the anticorrelation of the two endpoints' normal errors is not kept.
#pragma once

#include <Eigen/Core>

#include "robot/vision/lines/line_moments.h"

namespace lineloc {

struct LineSegment {
  LineFit fit;
  PointMoments moments;                                    // supporting edge points
  Eigen::Vector2d gradient_sum = Eigen::Vector2d::Zero();  // dark -> bright
  double step_sum = 0.0;                                   // grey-level steps
  double start_along = 0.0;
  double end_along = 0.0;
  double start_sigma_along_px = 1.0;
  double end_sigma_along_px = 1.0;

  Eigen::Vector2d start() const { return fit.centroid + start_along * fit.direction; }
  Eigen::Vector2d end() const { return fit.centroid + end_along * fit.direction; }
  double length() const { return end_along - start_along; }
  // Mean grey-level step across the segment.
  double contrast() const { return moments.n > 0.0 ? step_sum / moments.n : 0.0; }
  // +1 when the left side (start -> end, y down) is brighter, -1 when darker.
  int polarity() const;
  Eigen::Matrix2d startCovariance() const;
  Eigen::Matrix2d endCovariance() const;

  // Sets start/end to the extreme projections of the two points on the line.
  void setExtent(const Eigen::Vector2d& a, const Eigen::Vector2d& b);
};

}  // namespace lineloc
