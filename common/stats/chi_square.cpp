#include "common/stats/chi_square.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/stats/bisection_quantile.h"

namespace lineloc {
namespace {

constexpr int kMaxIterations = 10'000;
constexpr double kEpsilon = 1e-15;
constexpr double kTiny = std::numeric_limits<double>::min() / kEpsilon;

// P(a, x) = e^-x x^a / Gamma(a+1) * sum_n x^n / ((a+1)...(a+n)), for x < a + 1.
double lowerGammaSeries(double a, double x) {
  double term = 1.0 / a;
  double sum = term;
  for (int n = 1; n < kMaxIterations && std::abs(term) > std::abs(sum) * kEpsilon; ++n) {
    term *= x / (a + n);
    sum += term;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) = 1 - P(a, x) by the continued fraction (modified Lentz), for x >= a + 1.
double upperGammaFraction(double a, double x) {
  double b = x + 1.0 - a;
  double c = 1.0 / kTiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < kMaxIterations; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    d = std::abs(d) < kTiny ? kTiny : d;
    c = b + an / c;
    c = std::abs(c) < kTiny ? kTiny : c;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < kEpsilon) {
      break;
    }
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

double chiSquareCdf(double x, double degrees_of_freedom) {
  if (x <= 0.0) {
    return 0.0;
  }
  const double a = 0.5 * degrees_of_freedom;
  const double half_x = 0.5 * x;
  return half_x < a + 1.0 ? lowerGammaSeries(a, half_x) : 1.0 - upperGammaFraction(a, half_x);
}

double chiSquareQuantile(double probability, double degrees_of_freedom) {
  if (!(probability > 0.0 && probability < 1.0) || !(degrees_of_freedom > 0.0)) {
    throw std::invalid_argument("chiSquareQuantile: need 0 < probability < 1 and dof > 0");
  }
  return bisectionQuantile(
      [degrees_of_freedom](double x) { return chiSquareCdf(x, degrees_of_freedom); }, probability,
      degrees_of_freedom + 10.0 * std::sqrt(2.0 * degrees_of_freedom) + 100.0);
}

}  // namespace lineloc
