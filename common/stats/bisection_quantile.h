// The quantile of a continuous distribution from its CDF: the x in [0, upper]
// with cdf(x) = probability, found by bisection to a relative accuracy of
// 1e-12; `upper` doubles first until the CDF passes the probability. Serves
// distributions on [0, inf) whose CDF has no closed-form inverse.
#pragma once

namespace lineloc {

template <typename Cdf>
double bisectionQuantile(const Cdf& cdf, double probability, double upper) {
  while (cdf(upper) < probability) {
    upper *= 2.0;
  }
  double lower = 0.0;
  while (upper - lower > 1e-12 * upper) {
    const double middle = 0.5 * (lower + upper);
    if (cdf(middle) < probability) {
      lower = middle;
    } else {
      upper = middle;
    }
  }
  return 0.5 * (lower + upper);
}

}  // namespace lineloc
