// The heading a set of compass readings agree on, robust to a disturbance
// (steel, a parked car, a power line shifting the field by 10-40 degrees for
// seconds) that covers fewer than half of them: the circular median
//   m = argmin_i sum_j |wrap(psi_j - psi_i)|
// over the readings, then the circular mean atan2(sum sin psi_j, sum cos psi_j)
// of the readings within `gate_rad` of m: a disturbance that starts part-way
// through a start-up window leaves the heading alone, where it would pull a
// plain mean by a third of its size.
#pragma once

#include <vector>

namespace lineloc {

struct RobustHeading {
  double heading_rad = 0.0;
  // Readings within the gate of the median, which the mean is of.
  int inliers = 0;
};

// Throws std::invalid_argument when `headings_rad` is empty or `gate_rad` not > 0.
RobustHeading robustCircularMean(const std::vector<double>& headings_rad, double gate_rad);

}  // namespace lineloc
