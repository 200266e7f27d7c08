#include "robot/inertial/robust_heading.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "robot/inertial/measurement_models.h"

namespace lineloc {
namespace {

// sum_j |wrap(psi_j - psi)|.
double summedDeviation(const std::vector<double>& headings_rad, double heading_rad) {
  double sum = 0.0;
  for (const double other : headings_rad) {
    sum += std::abs(wrapAngle(other - heading_rad));
  }
  return sum;
}

double circularMedian(const std::vector<double>& headings_rad) {
  double median = headings_rad.front();
  double least = std::numeric_limits<double>::infinity();
  for (const double heading : headings_rad) {
    const double deviation = summedDeviation(headings_rad, heading);
    if (deviation < least) {
      least = deviation;
      median = heading;
    }
  }
  return median;
}

}  // namespace

RobustHeading robustCircularMean(const std::vector<double>& headings_rad, double gate_rad) {
  if (headings_rad.empty()) {
    throw std::invalid_argument("robustCircularMean: no headings");
  }
  if (!(gate_rad > 0.0)) {
    throw std::invalid_argument("robustCircularMean: gate_rad must be > 0");
  }
  const double median = circularMedian(headings_rad);
  double sum_sin = 0.0;
  double sum_cos = 0.0;
  int inliers = 0;
  for (const double heading : headings_rad) {
    if (std::abs(wrapAngle(heading - median)) <= gate_rad) {
      sum_sin += std::sin(heading);
      sum_cos += std::cos(heading);
      ++inliers;
    }
  }
  return {std::atan2(sum_sin, sum_cos), inliers};
}

}  // namespace lineloc
