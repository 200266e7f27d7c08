#include "common/stats/chi_square.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace lineloc {
namespace {

// Reference quantiles from standard tables (R: qchisq(p, k)), to 1e-9 relative.
TEST(ChiSquare, QuantilesMatchTables) {
  EXPECT_NEAR(chiSquareQuantile(0.95, 1), 3.841458820694124, 1e-9);
  EXPECT_NEAR(chiSquareQuantile(0.95, 10), 18.307038053275146, 1e-8);
  EXPECT_NEAR(chiSquareQuantile(0.999, 6), 22.457744484825323, 1e-8);
  EXPECT_NEAR(chiSquareQuantile(0.025, 3), 0.2157952826238981, 1e-10);
}

// For even k = 2m the CDF has a closed form: 1 - e^(-x/2) sum_{j<m} (x/2)^j / j!.
TEST(ChiSquare, CdfMatchesClosedFormForEvenDof) {
  for (const int dof : {2, 6, 30, 150}) {
    for (const double x : {0.5, 5.0, 25.0, 185.8}) {
      double sum = 0.0;
      double term = 1.0;
      for (int j = 0; j < dof / 2; ++j) {
        sum += term;
        term *= 0.5 * x / (j + 1);
      }
      EXPECT_NEAR(chiSquareCdf(x, dof), 1.0 - std::exp(-0.5 * x) * sum, 1e-12)
          << "dof " << dof << " x " << x;
    }
  }
}

TEST(ChiSquare, CdfInvertsQuantile) {
  for (const double dof : {1.0, 2.0, 6.0, 15.0, 750.0}) {
    for (const double p : {0.01, 0.5, 0.975, 0.9999}) {
      EXPECT_NEAR(chiSquareCdf(chiSquareQuantile(p, dof), dof), p, 1e-10);
    }
  }
}

TEST(ChiSquare, RejectsBadArguments) {
  EXPECT_THROW(chiSquareQuantile(1.0, 3), std::invalid_argument);
  EXPECT_THROW(chiSquareQuantile(0.5, 0), std::invalid_argument);
  EXPECT_EQ(chiSquareCdf(-1.0, 3), 0.0);
}

}  // namespace
}  // namespace lineloc
