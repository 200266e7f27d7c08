#include "common/geodesy/solar_position.h"

#include <cmath>
#include <numbers>

namespace lineloc {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kDaysPerJulianCentury = 36525.0;
// 2000-01-01 12:00:00 UTC as a Unix time (s).
constexpr int64_t kJ2000UnixS = 946'728'000;
constexpr int64_t kNsPerDay = 86'400'000'000'000;

double normalizedDegrees(double angle_deg) {
  const double wrapped = std::fmod(angle_deg, 360.0);
  return wrapped < 0.0 ? wrapped + 360.0 : wrapped;
}

}  // namespace

double daysSinceJ2000(int64_t unix_ns) {
  const int64_t since_ns = unix_ns - kJ2000UnixS * 1'000'000'000;
  return static_cast<double>(since_ns / kNsPerDay) +
         static_cast<double>(since_ns % kNsPerDay) / static_cast<double>(kNsPerDay);
}

SunEquatorial sunEquatorial(double days_since_j2000) {
  const double T = days_since_j2000 / kDaysPerJulianCentury;
  const double L0 = 280.46646 + T * (36000.76983 + T * 0.0003032);
  const double M = (357.52911 + T * (35999.05029 - T * 0.0001537)) * kDegree;
  const double C = (1.914602 - T * (0.004817 + T * 0.000014)) * std::sin(M) +
                   (0.019993 - T * 0.000101) * std::sin(2.0 * M) + 0.000289 * std::sin(3.0 * M);
  const double Omega = (125.04 - 1934.136 * T) * kDegree;
  const double lambda = (L0 + C - 0.00569 - 0.00478 * std::sin(Omega)) * kDegree;
  const double eps0 =
      23.0 + (26.0 + (21.448 - T * (46.8150 + T * (0.00059 - T * 0.001813))) / 60.0) / 60.0;
  const double eps = (eps0 + 0.00256 * std::cos(Omega)) * kDegree;
  return {
      normalizedDegrees(std::atan2(std::cos(eps) * std::sin(lambda), std::cos(lambda)) / kDegree),
      std::asin(std::sin(eps) * std::sin(lambda)) / kDegree};
}

double greenwichMeanSiderealTime_deg(double days_since_j2000) {
  const double T = days_since_j2000 / kDaysPerJulianCentury;
  return normalizedDegrees(280.46061837 + 360.98564736629 * days_since_j2000 +
                           T * T * (0.000387933 - T / 38710000.0));
}

double atmosphericRefraction_deg(double true_elevation_deg, double pressure_hpa,
                                 double temperature_c) {
  if (true_elevation_deg < -1.0) {
    return 0.0;
  }
  const double h = true_elevation_deg;
  const double standard_arcmin = 1.02 / std::tan((h + 10.3 / (h + 5.11)) * kDegree);
  return standard_arcmin / 60.0 * (pressure_hpa / 1010.0) * (283.0 / (273.0 + temperature_c));
}

SolarPosition solarPosition(int64_t unix_ns, const GeodeticPosition& place) {
  const double days = daysSinceJ2000(unix_ns);
  const SunEquatorial sun = sunEquatorial(days);
  const double H =
      (greenwichMeanSiderealTime_deg(days) + place.longitude_deg - sun.right_ascension_deg) *
      kDegree;
  const double phi = place.latitude_deg * kDegree;
  const double delta = sun.declination_deg * kDegree;
  const double elevation =
      std::asin(std::sin(phi) * std::sin(delta) + std::cos(phi) * std::cos(delta) * std::cos(H));
  const double azimuth_from_south =
      std::atan2(std::sin(H), std::cos(H) * std::sin(phi) - std::tan(delta) * std::cos(phi));
  SolarPosition position;
  position.azimuth_deg = normalizedDegrees(azimuth_from_south / kDegree + 180.0);
  position.elevation_deg = elevation / kDegree;
  position.apparent_elevation_deg =
      position.elevation_deg + atmosphericRefraction_deg(position.elevation_deg);
  return position;
}

}  // namespace lineloc
