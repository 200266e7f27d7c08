// The start-up heading from compass readings: the mean when they agree, the
// majority when a disturbance covers fewer than half of them, across the
// +-pi wrap, and a clear error on no readings.
#include "robot/inertial/robust_heading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "robot/inertial/measurement_models.h"

namespace lineloc {
namespace {

constexpr double kDeg = M_PI / 180.0;
// The compass's white noise and the gate the navigator uses (3 sigma).
constexpr double kCompassSigmaRad = 2.0 * kDeg;
constexpr double kGateRad = 3.0 * kCompassSigmaRad;

std::vector<double> noisyReadings(double heading_rad, int count, std::mt19937& random) {
  std::normal_distribution<double> noise(0.0, kCompassSigmaRad);
  std::vector<double> readings;
  for (int i = 0; i < count; ++i) {
    readings.push_back(wrapAngle(heading_rad + noise(random)));
  }
  return readings;
}

// Tolerance: 4 sigma of the mean of n readings, sigma / sqrt(n).
double meanTolerance(int count) {
  return 4.0 * kCompassSigmaRad / std::sqrt(static_cast<double>(count));
}

TEST(RobustCircularMean, IsTheMeanOfAgreeingReadings) {
  std::mt19937 random(1);
  const std::vector<double> readings = noisyReadings(0.9, 20, random);
  const RobustHeading mean = robustCircularMean(readings, kGateRad);
  EXPECT_NEAR(mean.heading_rad, 0.9, meanTolerance(20));
  // Each reading lies within the 3 sigma gate with probability 0.997.
  EXPECT_GE(mean.inliers, 19);
}

TEST(RobustCircularMean, IgnoresADisturbanceOverFewerThanHalfTheReadings) {
  std::mt19937 random(2);
  // 1.4 s of the true heading, then 0.6 s disturbed by 34 degrees (seed 30's start).
  std::vector<double> readings = noisyReadings(0.9, 14, random);
  const std::vector<double> disturbed = noisyReadings(0.9 - 34.0 * kDeg, 6, random);
  readings.insert(readings.end(), disturbed.begin(), disturbed.end());
  const RobustHeading mean = robustCircularMean(readings, kGateRad);
  EXPECT_NEAR(mean.heading_rad, 0.9, meanTolerance(14));
  EXPECT_GE(mean.inliers, 12);  // none of the 6 disturbed ones
  EXPECT_LE(mean.inliers, 14);
}

TEST(RobustCircularMean, AveragesAcrossTheWrap) {
  std::mt19937 random(3);
  const std::vector<double> readings = noisyReadings(M_PI - 1.0 * kDeg, 30, random);
  const RobustHeading mean = robustCircularMean(readings, kGateRad);
  EXPECT_NEAR(std::abs(wrapAngle(mean.heading_rad - (M_PI - 1.0 * kDeg))), 0.0, meanTolerance(30));
}

TEST(RobustCircularMean, RejectsNoReadingsAndABadGate) {
  EXPECT_THROW(robustCircularMean({}, kGateRad), std::invalid_argument);
  EXPECT_THROW(robustCircularMean({0.1}, 0.0), std::invalid_argument);
  EXPECT_THROW(robustCircularMean({0.1}, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
