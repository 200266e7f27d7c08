#include "common/stats/confidence_scale.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "common/stats/bisection_quantile.h"
#include "common/stats/chi_square.h"

namespace lineloc {

double confidenceScale(int redundancy, double probability) {
  if (redundancy < 1) {
    throw std::invalid_argument(
        fmt::format("confidence scale needs a redundancy of at least 1, not {}", redundancy));
  }
  const double chi_square = chiSquareQuantile(probability, 6.0);
  const double r = redundancy;
  const double b = 0.5 * r;
  const auto fisher_cdf = [r, b](double x) {
    const double w = 6.0 * x / (6.0 * x + r);
    return 1.0 - std::pow(1.0 - w, b) * (1.0 + b * w + 0.5 * b * (b + 1.0) * w * w);
  };
  return 6.0 * bisectionQuantile(fisher_cdf, probability, chi_square / 6.0) / chi_square;
}

}  // namespace lineloc
