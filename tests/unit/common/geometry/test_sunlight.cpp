// The sun's direction from azimuth and elevation, and Lambert's cosine law.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "common/geometry/sunlight.h"

namespace lineloc {
namespace {

TEST(Sunlight, AzimuthIsClockwiseFromNorthAndElevationAboveTheHorizon) {
  const Eigen::Vector3d east = Sunlight::fromAzimuthElevation(90, 0, 0.3).direction_world;
  EXPECT_NEAR((east - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-12);
  const Eigen::Vector3d north = Sunlight::fromAzimuthElevation(0, 0, 0.3).direction_world;
  EXPECT_NEAR((north - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-12);
  const Eigen::Vector3d zenith = Sunlight::fromAzimuthElevation(200, 90, 0.3).direction_world;
  EXPECT_NEAR((zenith - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-12);
  // South-west, 30 degrees up: (-cos 30 / sqrt 2, -cos 30 / sqrt 2, 1/2).
  const Eigen::Vector3d south_west = Sunlight::fromAzimuthElevation(225, 30, 0.3).direction_world;
  const double horizontal = std::sqrt(3.0) / 2.0 / std::sqrt(2.0);
  EXPECT_NEAR((south_west - Eigen::Vector3d(-horizontal, -horizontal, 0.5)).norm(), 0.0, 1e-12);
}

TEST(Sunlight, AzimuthAndElevationComeBackFromTheDirection) {
  for (const double azimuth_deg : {0.0, 45.0, 136.5, 225.0, 359.0}) {
    for (const double elevation_deg : {-10.0, 0.0, 39.6, 89.0}) {
      const Sunlight sun = Sunlight::fromAzimuthElevation(azimuth_deg, elevation_deg, 0.3);
      EXPECT_NEAR(sun.azimuth_deg(), azimuth_deg, 1e-9) << elevation_deg;
      EXPECT_NEAR(sun.elevation_deg(), elevation_deg, 1e-9) << azimuth_deg;
    }
  }
}

// E(n) = a + (1 - a) max(0, n . s) lit.
TEST(Sunlight, IrradianceFollowsLambertsCosineLawAboveTheAmbientShare) {
  const Sunlight sun = Sunlight::fromAzimuthElevation(180, 60, 0.35);  // south, 60 degrees up
  EXPECT_NEAR(sun.irradiance(Eigen::Vector3d::UnitZ(), false), 0.35 + 0.65 * std::sqrt(3.0) / 2.0,
              1e-12);
  EXPECT_NEAR(sun.irradiance(-Eigen::Vector3d::UnitY(), false), 0.35 + 0.65 * 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(sun.irradiance(Eigen::Vector3d::UnitY(), false), 0.35);  // north wall: shade
  EXPECT_DOUBLE_EQ(sun.irradiance(-Eigen::Vector3d::UnitZ(), false), 0.35);
  EXPECT_DOUBLE_EQ(sun.irradiance(Eigen::Vector3d::UnitZ(), true), 0.35);  // a cast shadow
}

TEST(Sunlight, RejectsAnElevationOrAmbientShareOutOfRange) {
  EXPECT_THROW(Sunlight::fromAzimuthElevation(0, 91, 0.3), std::invalid_argument);
  EXPECT_THROW(Sunlight::fromAzimuthElevation(0, std::nan(""), 0.3), std::invalid_argument);
  EXPECT_THROW(Sunlight::fromAzimuthElevation(INFINITY, 10, 0.3), std::invalid_argument);
  EXPECT_THROW(Sunlight::fromAzimuthElevation(0, 10, -0.1), std::invalid_argument);
  EXPECT_THROW(Sunlight::fromAzimuthElevation(0, 10, 1.5), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
