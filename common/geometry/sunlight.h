// Direct sunlight plus a uniform ambient share on a Lambertian surface, the
// shading model the simulator renders with and the backbone predicts edges
// from. With s the unit vector towards the sun and a the ambient fraction, a
// surface whose outward unit normal is n receives, relative to full sun,
//   E(n) = a + (1 - a) max(0, n . s) lit         (Lambert's cosine law),
// lit = 0 where another surface stands between it and the sun (a cast
// shadow; finding those is the caller's ray casting), 1 elsewhere.
//
// World frame: the site's, x east (grid), y north (grid), z up.
#pragma once

#include <Eigen/Core>

namespace lineloc {

struct Sunlight {
  Eigen::Vector3d direction_world = Eigen::Vector3d::UnitZ();  // unit, towards the sun
  double ambient_fraction = 0.35;

  // The sun at `azimuth_deg` clockwise from grid north and `elevation_deg`
  // above the horizon: s = (sin az cos el, cos az cos el, sin el).
  static Sunlight fromAzimuthElevation(double azimuth_deg, double elevation_deg,
                                       double ambient_fraction);

  // The inverse: azimuth clockwise from grid north (0..360) and elevation (deg).
  double azimuth_deg() const;
  double elevation_deg() const;

  // E(n) above; `unit_normal` is the side of the surface that is seen.
  double irradiance(const Eigen::Vector3d& unit_normal, bool in_shadow) const;
};

}  // namespace lineloc
