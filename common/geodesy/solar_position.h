// Where the sun stands in the sky at a time and place: J. Meeus, "Astronomical
// Algorithms", 2nd ed., Willmann-Bell 1998, chapter 25's lower-accuracy solar
// coordinates (geometric mean longitude L0 (25.2), mean anomaly M (25.3),
// equation of centre C, apparent longitude lambda = L0 + C - 0.00569 -
// 0.00478 sin Omega, obliquity eps = eps0 (22.2) + 0.00256 cos Omega (25.8),
// then alpha = atan2(cos eps sin lambda, cos lambda) and
// sin delta = sin eps sin lambda (25.6, 25.7)), accurate to 0.01 degree; the
// mean sidereal time at Greenwich (12.4); and the horizontal coordinates of
// chapter 13 with the local hour angle H = theta0 + longitude - alpha:
//   sin h = sin phi sin delta + cos phi cos delta cos H              (13.6)
//   A = atan2(sin H, cos H sin phi - tan delta cos phi) + 180 deg   (13.5)
// (A clockwise from true north). Atmospheric refraction is Saemundsson's
// formula (16.4) for the standard atmosphere, 1010 hPa and 10 degrees C,
// scaled by P / 1010 * 283 / (273 + T).
//
// Time is UT from a Unix time stamp: the difference to dynamical time
// (about a minute) moves the sun by 0.0007 degree, within the stated accuracy.
#pragma once

#include <cstdint>

#include "common/geodesy/site_projection.h"

namespace lineloc {

// Days since J2000.0 (2000-01-01 12:00 UT) of a Unix time stamp.
double daysSinceJ2000(int64_t unix_ns);

// Apparent geocentric right ascension and declination of the sun (degrees).
struct SunEquatorial {
  double right_ascension_deg = 0.0;
  double declination_deg = 0.0;
};
SunEquatorial sunEquatorial(double days_since_j2000);

// Mean sidereal time at Greenwich (degrees, 0..360).
double greenwichMeanSiderealTime_deg(double days_since_j2000);

// Refraction R (degrees) that lifts a body at true elevation h (degrees) to
// h + R; 0 below one degree under the horizon, where the formula diverges.
double atmosphericRefraction_deg(double true_elevation_deg, double pressure_hpa = 1010.0,
                                 double temperature_c = 10.0);

struct SolarPosition {
  double azimuth_deg = 0.0;             // clockwise from true north, 0..360
  double elevation_deg = 0.0;           // geometric, above the horizon
  double apparent_elevation_deg = 0.0;  // with the standard atmosphere's refraction
};

// The sun seen from `place` (its height does not matter at 0.01 degree).
SolarPosition solarPosition(int64_t unix_ns, const GeodeticPosition& place);

}  // namespace lineloc
