#include "common/stats/confidence_scale.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace lineloc {
namespace {

TEST(ConfidenceScale, FisherQuantilesMatchTheTables) {
  // F_0.95(6, 10) = 3.2172 and F_0.99(6, 20) = 3.8714.
  EXPECT_NEAR(confidenceScale(10, 0.95), 6.0 * 3.2172 / 12.5916, 1e-4);
  EXPECT_NEAR(confidenceScale(20, 0.99), 6.0 * 3.8714 / 16.8119, 1e-4);
}

TEST(ConfidenceScale, ShrinksToOneAsTheRedundancyGrows) {
  double previous = confidenceScale(1, 0.9973);
  for (const int redundancy : {2, 6, 18, 50, 200, 1000}) {
    const double scale = confidenceScale(redundancy, 0.9973);
    EXPECT_LT(scale, previous) << redundancy;
    EXPECT_GT(scale, 1.0) << redundancy;
    previous = scale;
  }
  EXPECT_NEAR(confidenceScale(18, 0.9973), 1.58, 0.01);
  EXPECT_NEAR(confidenceScale(1'000'000, 0.9973), 1.0, 1e-3);
}

TEST(ConfidenceScale, RefusesWhatHasNoQuantile) {
  EXPECT_THROW(confidenceScale(0, 0.9973), std::invalid_argument);
  EXPECT_THROW(confidenceScale(10, 0.0), std::invalid_argument);
  EXPECT_THROW(confidenceScale(10, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
