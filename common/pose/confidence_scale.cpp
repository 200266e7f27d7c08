#include "common/pose/confidence_scale.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace lineloc {
namespace {

constexpr int kBisections = 200;

// The x in [0, upper] where an increasing cdf reaches `probability`; `upper`
// doubles until the cdf passes it.
template <typename Cdf>
double quantile(const Cdf& cdf, double probability) {
  double upper = 1.0;
  while (cdf(upper) < probability) {
    upper *= 2.0;
  }
  double lower = 0.0;
  for (int i = 0; i < kBisections && upper - lower > 1e-12 * upper; ++i) {
    const double middle = 0.5 * (lower + upper);
    if (cdf(middle) < probability) {
      lower = middle;
    } else {
      upper = middle;
    }
  }
  return 0.5 * (lower + upper);
}

void requireProbability(double probability) {
  if (!(probability > 0.0 && probability < 1.0)) {
    throw std::invalid_argument(
        fmt::format("confidence probability {} is not in (0, 1)", probability));
  }
}

}  // namespace

double chiSquare6Quantile(double probability) {
  requireProbability(probability);
  return quantile(
      [](double y) { return 1.0 - std::exp(-0.5 * y) * (1.0 + 0.5 * y + 0.125 * y * y); },
      probability);
}

double confidenceScale(int redundancy, double probability) {
  requireProbability(probability);
  if (redundancy < 1) {
    throw std::invalid_argument(
        fmt::format("confidence scale needs a redundancy of at least 1, not {}", redundancy));
  }
  const double r = redundancy;
  const double b = 0.5 * r;
  const auto fisher_cdf = [r, b](double x) {
    const double w = 6.0 * x / (6.0 * x + r);
    return 1.0 - std::pow(1.0 - w, b) * (1.0 + b * w + 0.5 * b * (b + 1.0) * w * w);
  };
  return 6.0 * quantile(fisher_cdf, probability) / chiSquare6Quantile(probability);
}

}  // namespace lineloc
