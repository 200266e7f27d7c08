// The sun's place against published worked examples: Meeus' own (the same
// method, so to their printed digits) and NREL's SPA (Reda and Andreas, Solar
// Energy 76, 2004: a 0.0003 degree algorithm, so within Meeus' 0.01 degree).
#include "common/geodesy/solar_position.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/time/utc_time.h"

namespace lineloc {
namespace {

constexpr double kJ2000JulianDay = 2451545.0;

TEST(SolarPosition, DaysSinceJ2000CountFromNoonOfNewYear2000) {
  EXPECT_DOUBLE_EQ(daysSinceJ2000(parseUtcTime_ns("2000-01-01T12:00:00Z")), 0.0);
  EXPECT_DOUBLE_EQ(daysSinceJ2000(parseUtcTime_ns("1992-10-13T00:00:00Z")),
                   2448908.5 - kJ2000JulianDay);
  EXPECT_DOUBLE_EQ(daysSinceJ2000(parseUtcTime_ns("2026-05-21T18:00:00Z")), 9637.25);
}

TEST(SolarPosition, SunMatchesMeeusExample25a) {
  // 1992 October 13.0: alpha 13h13m31.4s = 198.38083 deg, delta -7.78507 deg.
  const SunEquatorial sun = sunEquatorial(2448908.5 - kJ2000JulianDay);
  EXPECT_NEAR(sun.right_ascension_deg, 198.38083, 1e-5);
  EXPECT_NEAR(sun.declination_deg, -7.78507, 1e-5);
}

TEST(SolarPosition, SiderealTimeMatchesMeeusExamples12aAnd12b) {
  // 1987 April 10, 0h UT: 13h10m46.3668s; 19h21m00s UT: 128.7378734 deg.
  EXPECT_NEAR(greenwichMeanSiderealTime_deg(2446895.5 - kJ2000JulianDay), 197.693195, 1e-6);
  EXPECT_NEAR(
      greenwichMeanSiderealTime_deg(daysSinceJ2000(parseUtcTime_ns("1987-04-10T19:21:00Z"))),
      128.7378734, 1e-6);
}

TEST(SolarPosition, MatchesTheNrelSpaWorkedExample) {
  // Golden, Colorado, 2003-10-17 12:30:30 at UTC-7: topocentric elevation
  // 39.872046 deg before refraction, azimuth 194.340241 deg. Meeus' 0.01 deg
  // plus the sun's parallax (8.8 arcsec), which the geocentric method omits.
  constexpr double kTolerance_deg = 0.01 + 8.8 / 3600.0;
  const SolarPosition sun =
      solarPosition(parseUtcTime_ns("2003-10-17T19:30:30Z"), {39.742476, -105.1786, 1830.14});
  EXPECT_NEAR(sun.elevation_deg, 39.872046, kTolerance_deg);
  EXPECT_NEAR(sun.azimuth_deg, 194.340241, kTolerance_deg);
  EXPECT_NEAR(sun.apparent_elevation_deg - sun.elevation_deg,
              atmosphericRefraction_deg(sun.elevation_deg), 1e-12);
}

TEST(SolarPosition, RefractionMatchesSpaAndTheHorizon) {
  // SPA's refraction of the example at 820 hPa and 11 degrees C: 0.016332 deg;
  // Saemundsson's formula follows Bennett's to 0.1 arcmin.
  constexpr double kBennett_deg = 0.1 / 60.0;
  EXPECT_NEAR(atmosphericRefraction_deg(39.872046, 820.0, 11.0), 0.016332, kBennett_deg);
  // The standard atmosphere lifts the sun 34.5 arcmin below the horizon onto it.
  EXPECT_NEAR(atmosphericRefraction_deg(-34.5 / 60.0), 34.5 / 60.0, kBennett_deg);
  EXPECT_LT(atmosphericRefraction_deg(90.0), kBennett_deg);
  EXPECT_EQ(atmosphericRefraction_deg(-10.0), 0.0);
}

TEST(SolarPosition, NoonStandsDueSouthAtNinetyMinusLatitudePlusDeclination) {
  // Over a midsummer day in Delft the highest sun is in the meridian, at
  // 90 - phi + delta: the horizontal coordinates, independent of the ephemeris.
  const GeodeticPosition delft{52.0127, 4.3556, 0.0};
  const int64_t midnight_ns = parseUtcTime_ns("2026-06-21T00:00:00Z");
  int64_t highest_ns = midnight_ns;
  double highest_deg = -90.0;
  for (int64_t t_ns = midnight_ns; t_ns < midnight_ns + 86'400'000'000'000; t_ns += 1'000'000'000) {
    const double elevation_deg = solarPosition(t_ns, delft).elevation_deg;
    if (elevation_deg > highest_deg) {
      highest_deg = elevation_deg;
      highest_ns = t_ns;
    }
  }
  const SolarPosition noon = solarPosition(highest_ns, delft);
  const double declination_deg = sunEquatorial(daysSinceJ2000(highest_ns)).declination_deg;
  EXPECT_NEAR(noon.elevation_deg, 90.0 - delft.latitude_deg + declination_deg, 1e-6);
  // One second of the earth's turn is 0.004 deg of hour angle; near the
  // meridian the azimuth turns about 1.9 times as fast at this height.
  EXPECT_NEAR(noon.azimuth_deg, 180.0, 0.01);
  // Local noon at 4.36 deg east is 17.4 min before 12:00 UT, give or take the
  // equation of time (-1.7 min at the June solstice).
  EXPECT_NEAR((highest_ns - midnight_ns) * 1e-9 / 60.0, 12 * 60 - 4.3556 * 4 + 1.7, 0.5);
}

}  // namespace
}  // namespace lineloc
