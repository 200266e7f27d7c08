// How much a 6-DoF pose covariance estimated from its own residuals must be
// widened for its chi^2_6 confidence region to hold at a stated probability.
//
// A covariance scaled by the a-posteriori variance factor s^2, estimated with
// r = 2n - 6 degrees of freedom from n line correspondences, makes the
// Mahalanobis form e^T C^-1 e / 6 of the pose error Fisher distributed,
// F(6, r), instead of chi^2_6 / 6: the confidence region of a least-squares
// estimate with an estimated variance factor (Koch, "Parameter Estimation and
// Hypothesis Testing in Linear Models", 1999; Förstner & Wrobel,
// "Photogrammetric Computer Vision", 2016, ch. 4). Its p-quantile is the
// larger the fewer the correspondences: at
// p = 0.9973, 6 F_p(6, 18) = 1.58 chi^2_6(p). Scaling C by
//   k(r, p) = 6 F_p(6, r) / chi^2_6(p)
// makes a chi^2_6(p) gate on the scaled covariance hold at p. With six
// numerator degrees of freedom the Fisher CDF has a closed form,
//   P(F(6, r) <= x) = 1 - (1 - w)^b (1 + b w + b (b + 1) w^2 / 2),
// with w = 6x / (6x + r) and b = r / 2 (the Beta(3, b) distribution of w with
// an integer first parameter), inverted by bisection (bisection_quantile.h);
// chi^2_6(p) is chi_square.h's.
#pragma once

namespace lineloc {

// 6 F_p(6, r) / chi^2_6(p) for redundancy r >= 1 and p in (0, 1); throws
// std::invalid_argument otherwise. Tends to 1 as r grows.
double confidenceScale(int redundancy, double probability);

}  // namespace lineloc
