// The sun over a site: the solar position at the site's place, turned into
// the site's grid.
#include "common/geodesy/site_sun.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "common/geodesy/solar_position.h"
#include "common/time/utc_time.h"

namespace lineloc {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

TEST(SiteSun, OnTheCentralMeridianGridNorthIsTrueNorth) {
  // UTM 31N's central meridian is 3 deg east: 500 km easting.
  const SiteProjection site("UTM:31N", {500'000.0, 5'763'000.0, 0.0});
  const SiteSun sun_over_site(site, 0.35);
  const int64_t morning_ns = parseUtcTime_ns("2026-05-21T08:30:00Z");
  const SolarPosition sun = solarPosition(morning_ns, sun_over_site.place());
  const std::optional<Sunlight> light = sun_over_site.at(morning_ns);
  ASSERT_TRUE(light.has_value());
  EXPECT_NEAR(sun_over_site.place().longitude_deg, 3.0, 1e-9);
  EXPECT_NEAR(light->azimuth_deg(), sun.azimuth_deg, 1e-9);
  EXPECT_NEAR(light->elevation_deg(), sun.apparent_elevation_deg, 1e-9);
  EXPECT_DOUBLE_EQ(light->ambient_fraction, 0.35);
}

TEST(SiteSun, GridAzimuthIsTrueAzimuthPlusTheGridBearingOfNorth) {
  // 60 km east of the central meridian at 52 deg north grid north lies about
  // 0.7 deg east of true north, so true north bears -0.7 deg on the grid.
  const SiteProjection site("UTM:31N", {560'000.0, 5'763'000.0, 0.0});
  const SiteSun sun_over_site(site, 0.35);
  const int64_t afternoon_ns = parseUtcTime_ns("2026-09-01T13:00:00Z");
  const double grid_bearing_deg = site.gridBearingOfTrueNorth_rad(sun_over_site.place()) / kDegree;
  EXPECT_LT(grid_bearing_deg, -0.5);
  EXPECT_NEAR(sun_over_site.at(afternoon_ns)->azimuth_deg(),
              solarPosition(afternoon_ns, sun_over_site.place()).azimuth_deg + grid_bearing_deg,
              1e-9);
}

TEST(SiteSun, NoSunlightAtNight) {
  const SiteSun sun_over_site(SiteProjection("UTM:31N", {593'000.0, 5'763'000.0, 0.0}), 0.35);
  EXPECT_FALSE(sun_over_site.at(parseUtcTime_ns("2026-05-21T23:00:00Z")).has_value());
  EXPECT_TRUE(sun_over_site.at(parseUtcTime_ns("2026-05-21T12:00:00Z")).has_value());
}

TEST(SiteSun, RefusesAnAmbientFractionOutsideZeroToOne) {
  const SiteProjection site("UTM:31N", {593'000.0, 5'763'000.0, 0.0});
  EXPECT_THROW(SiteSun(site, 1.5), std::invalid_argument);
  EXPECT_THROW(SiteSun(site, -0.1), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
