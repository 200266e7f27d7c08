#include "common/geometry/sunlight.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lineloc {

Sunlight Sunlight::fromAzimuthElevation(double azimuth_deg, double elevation_deg,
                                        double ambient_fraction) {
  if (!std::isfinite(azimuth_deg) || !(elevation_deg >= -90.0 && elevation_deg <= 90.0)) {
    throw std::invalid_argument("sun azimuth must be finite and elevation within [-90, 90] deg");
  }
  if (!(ambient_fraction >= 0.0 && ambient_fraction <= 1.0)) {
    throw std::invalid_argument("ambient fraction must lie within [0, 1]");
  }
  constexpr double kDegree = M_PI / 180.0;
  const double azimuth = azimuth_deg * kDegree;
  const double elevation = elevation_deg * kDegree;
  return {Eigen::Vector3d(std::sin(azimuth) * std::cos(elevation),
                          std::cos(azimuth) * std::cos(elevation), std::sin(elevation)),
          ambient_fraction};
}

double Sunlight::azimuth_deg() const {
  const double azimuth_deg = std::atan2(direction_world.x(), direction_world.y()) * 180.0 / M_PI;
  return azimuth_deg < 0.0 ? azimuth_deg + 360.0 : azimuth_deg;
}

double Sunlight::elevation_deg() const {
  return std::asin(direction_world.z()) * 180.0 / M_PI;
}

double Sunlight::irradiance(const Eigen::Vector3d& unit_normal, bool in_shadow) const {
  const double lit = in_shadow ? 0.0 : 1.0;
  return ambient_fraction +
         (1.0 - ambient_fraction) * std::max(0.0, unit_normal.dot(direction_world)) * lit;
}

}  // namespace lineloc
