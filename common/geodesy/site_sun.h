// The sun over a site at a time, as the Sunlight its faces are lit with
// (common/geometry/sunlight.h): solarPosition (solar_position.h) at the site
// origin's geodetic place, its azimuth turned from true to grid north, the
// site frame's y (grid bearing = true bearing + gridBearingOfTrueNorth_rad).
// One place serves the whole site: 10 km move the sun by 0.1 degree.
#pragma once

#include <cstdint>
#include <optional>

#include "common/geodesy/site_projection.h"
#include "common/geometry/sunlight.h"

namespace lineloc {

class SiteSun {
 public:
  // Throws std::invalid_argument for an ambient fraction outside [0, 1].
  SiteSun(const SiteProjection& site, double ambient_fraction);

  // Nullopt while the sun's apparent elevation is not above the horizon:
  // there is no direct light, and a uniform ambient share is no model of a
  // street at dusk.
  std::optional<Sunlight> at(int64_t unix_ns) const;

  const GeodeticPosition& place() const { return place_; }

 private:
  GeodeticPosition place_;
  double grid_bearing_of_true_north_deg_;
  double ambient_fraction_;
};

}  // namespace lineloc
