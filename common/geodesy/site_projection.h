// WGS84 geodetic coordinates <-> the site frame (DESIGN.md: the site's
// projected CRS, x east, y north, z up, minus the site origin), and the meridian
// convergence that turns a true-north bearing (compass, GPS course) into a grid
// bearing.
//
// Which library: UTM ("UTM:31N", or EPSG:326zz / 327zz) goes through
// GeographicLib's exact-to-nanometres Krüger series (Karney, "Transverse
// Mercator with an accuracy of a few nanometers", J. Geodesy 85, 2011), whose
// meridian convergence gamma comes with the projection. Any other EPSG CRS (RD
// New EPSG:28992, its compound EPSG:7415, ETRS89 / UTM EPSG:258zz, ...) goes
// through PROJ with the best transformation it has offline (for RD New, the
// published 7-parameter Helmert, about 1 m); its convergence is the grid
// bearing of a 1e-5 degree northward step, accurate to about 1e-7 rad.
//
// Heights are not transformed: z is the height above mean sea level (GGA's
// altitude, the same datum as NAP or a city model's heights to a few
// decimetres) minus the origin's z. A compound CRS uses its horizontal part.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

namespace lineloc {

// WGS84 latitude and longitude (degrees, north and east positive) and height
// above mean sea level (metres).
struct GeodeticPosition {
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double height_msl_m = 0.0;
};

class SiteProjectionBackend;

class SiteProjection {
 public:
  // `crs` is "UTM:<zone><N|S>" (e.g. "UTM:31N") or "EPSG:<code>" of a projected
  // or compound CRS; `origin` is the site origin in that CRS (easting,
  // northing, height). Throws std::invalid_argument naming the CRS when it is
  // unknown, not projected, or PROJ has no transformation to it.
  SiteProjection(const std::string& crs, const Eigen::Vector3d& origin);
  ~SiteProjection();
  SiteProjection(SiteProjection&&) noexcept;
  SiteProjection& operator=(SiteProjection&&) noexcept;

  // Site-frame point of a geodetic position. Throws std::domain_error when the
  // position is outside the projection's domain (non-finite result).
  Eigen::Vector3d toSite(const GeodeticPosition& position) const;
  GeodeticPosition toGeodetic(const Eigen::Vector3d& p_site) const;

  // Grid bearing of true north at `position`, clockwise from grid north
  // (radians): grid bearing = true bearing + this. It is minus the meridian
  // convergence gamma of GeographicLib (the bearing of grid north from true north).
  double gridBearingOfTrueNorth_rad(const GeodeticPosition& position) const;

  const std::string& crs() const { return crs_; }

 private:
  std::string crs_;
  Eigen::Vector3d origin_;
  std::unique_ptr<SiteProjectionBackend> backend_;
};

}  // namespace lineloc
