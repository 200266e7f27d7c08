// Chi-square distribution: CDF through the regularised lower incomplete gamma
// function P(k/2, x/2) (series and Lentz continued fraction, Press et al.,
// "Numerical Recipes", 3rd ed., §6.2) and its quantile by bisection. Used for
// Mahalanobis gates (computed once per measurement dimension) and for the
// NEES/NIS consistency bounds.
#pragma once

namespace lineloc {

double chiSquareCdf(double x, double degrees_of_freedom);

// The x with chiSquareCdf(x, dof) = probability, for 0 < probability < 1,
// to a relative accuracy of 1e-12.
double chiSquareQuantile(double probability, double degrees_of_freedom);

}  // namespace lineloc
