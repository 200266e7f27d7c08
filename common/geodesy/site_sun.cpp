#include "common/geodesy/site_sun.h"

#include <numbers>

#include "common/geodesy/solar_position.h"

namespace lineloc {

SiteSun::SiteSun(const SiteProjection& site, double ambient_fraction)
    : place_(site.toGeodetic(Eigen::Vector3d::Zero())),
      grid_bearing_of_true_north_deg_(site.gridBearingOfTrueNorth_rad(place_) * 180.0 /
                                      std::numbers::pi),
      // Validated once here, as Sunlight validates it.
      ambient_fraction_(
          Sunlight::fromAzimuthElevation(0.0, 90.0, ambient_fraction).ambient_fraction) {}

std::optional<Sunlight> SiteSun::at(int64_t unix_ns) const {
  const SolarPosition sun = solarPosition(unix_ns, place_);
  if (!(sun.apparent_elevation_deg > 0.0)) {
    return std::nullopt;
  }
  return Sunlight::fromAzimuthElevation(sun.azimuth_deg + grid_bearing_of_true_north_deg_,
                                        sun.apparent_elevation_deg, ambient_fraction_);
}

}  // namespace lineloc
