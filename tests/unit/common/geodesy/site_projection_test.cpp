#include "common/geodesy/site_projection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace lineloc {
namespace {

// Delft, Oude Kerk, and a site origin near it in UTM 31N.
const GeodeticPosition kDelft{52.0127, 4.3556, 1.5};
const Eigen::Vector3d kDelftUtmOrigin(593000.0, 5763000.0, 0.0);

TEST(SiteProjection, UtmRoundTripIsExact) {
  const SiteProjection utm("UTM:31N", kDelftUtmOrigin);
  const Eigen::Vector3d p_site = utm.toSite(kDelft);
  // The site frame is small: the point is within a kilometre of the origin.
  EXPECT_LT(p_site.head<2>().norm(), 1'000.0);
  EXPECT_DOUBLE_EQ(p_site.z(), 1.5);
  const GeodeticPosition back = utm.toGeodetic(p_site);
  // GeographicLib's series is accurate to 5 nm; 1e-10 deg is 11 micrometres.
  EXPECT_NEAR(back.latitude_deg, kDelft.latitude_deg, 1e-10);
  EXPECT_NEAR(back.longitude_deg, kDelft.longitude_deg, 1e-10);
}

TEST(SiteProjection, EpsgUtmCodeIsTheSameUtm) {
  const SiteProjection by_zone("UTM:31N", kDelftUtmOrigin);
  const SiteProjection by_epsg("EPSG:32631", kDelftUtmOrigin);
  EXPECT_EQ(by_zone.toSite(kDelft), by_epsg.toSite(kDelft));
}

TEST(SiteProjection, ProjAgreesWithGeographicLibOnEtrsUtm) {
  // ETRS89 and WGS84 are the same frame to PROJ without a time-dependent
  // transformation, so ETRS89 / UTM 31N through PROJ must match GeographicLib's
  // UTM to the millimetre, and their convergences to the numerical step's 1e-7 rad.
  const SiteProjection geographiclib("UTM:31N", kDelftUtmOrigin);
  const SiteProjection proj("EPSG:25831", kDelftUtmOrigin);
  EXPECT_LT((geographiclib.toSite(kDelft) - proj.toSite(kDelft)).norm(), 1e-3);
  EXPECT_NEAR(geographiclib.gridBearingOfTrueNorth_rad(kDelft),
              proj.gridBearingOfTrueNorth_rad(kDelft), 1e-7);
}

TEST(SiteProjection, ConvergenceSignAndSize) {
  const SiteProjection utm("UTM:31N", Eigen::Vector3d::Zero());
  // Zone 31's central meridian is 3 deg E: on it true north is grid north.
  EXPECT_NEAR(utm.gridBearingOfTrueNorth_rad({52.0, 3.0, 0.0}), 0.0, 1e-12);
  // East of it, meridians converge towards the pole to the grid's west, so true
  // north has a negative (anticlockwise) grid bearing; to first order
  // gamma = dlon sin(lat) = 1.3556 deg * sin(52.0127 deg) = 1.0685 deg.
  const double expected =
      -(kDelft.longitude_deg - 3.0) * std::sin(kDelft.latitude_deg * M_PI / 180.0);
  EXPECT_NEAR(utm.gridBearingOfTrueNorth_rad(kDelft) * 180.0 / M_PI, expected, 1e-3);
}

TEST(SiteProjection, RdNewMapsAmersfoortToItsOrigin) {
  // The RD origin, Amersfoort's Onze Lieve Vrouwetoren, is (155000, 463000) in
  // RD New and (52.15517440 N, 5.38720621 E) in WGS84 (RDNAPTRANS). PROJ's
  // offline Helmert transformation is good to about 1 m, so allow 2 m.
  const SiteProjection rd("EPSG:28992", Eigen::Vector3d(155000.0, 463000.0, 0.0));
  EXPECT_LT(rd.toSite({52.15517440, 5.38720621, 0.0}).head<2>().norm(), 2.0);
  // RD New is a stereographic projection centred on Amersfoort: no convergence there.
  EXPECT_NEAR(rd.gridBearingOfTrueNorth_rad({52.15517440, 5.38720621, 0.0}), 0.0, 1e-4);
  const SiteProjection compound("EPSG:7415", Eigen::Vector3d(155000.0, 463000.0, 0.0));
  EXPECT_LT((compound.toSite(kDelft) - rd.toSite(kDelft)).norm(), 1e-6);
  // PROJ inverts the Helmert step to first order only: 1e-8 deg is 1.1 mm.
  const GeodeticPosition back = rd.toGeodetic(rd.toSite(kDelft));
  EXPECT_NEAR(back.latitude_deg, kDelft.latitude_deg, 1e-8);
  EXPECT_NEAR(back.longitude_deg, kDelft.longitude_deg, 1e-8);
}

TEST(SiteProjection, RejectsUnknownCrsWithItsName) {
  for (const char* crs : {"UTM:61N", "UTM:31X", "EPSG:4326", "EPSG:999999", "WGS84", ""}) {
    try {
      SiteProjection projection(crs, Eigen::Vector3d::Zero());
      ADD_FAILURE() << "accepted '" << crs << "'";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(crs), std::string::npos) << error.what();
    }
  }
  EXPECT_THROW(SiteProjection("UTM:31N", Eigen::Vector3d(NAN, 0, 0)), std::invalid_argument);
}

TEST(SiteProjection, OutOfDomainIsAnError) {
  const SiteProjection utm("UTM:31N", Eigen::Vector3d::Zero());
  EXPECT_THROW(utm.toSite({95.0, 3.0, 0.0}), std::domain_error);
  EXPECT_THROW(utm.toSite({52.0, 120.0, 0.0}), std::domain_error);
}

}  // namespace
}  // namespace lineloc
