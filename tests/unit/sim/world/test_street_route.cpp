#include <gtest/gtest.h>

#include "sim/world/street_route.h"
#include "tests/unit/sim/world/box_city.h"

namespace lineloc {
namespace {

TEST(StreetRoute, DrivesTheStreetsKeepingClearOfFacades) {
  const OccupancyMap map(makeBoxCity(3, 14.0), 0.5);
  StreetRouteOptions options;
  options.length_m = 300.0;
  options.min_clearance_m = 3.0;
  const StreetRoute route = planStreetRoute(map, options);
  ASSERT_EQ(route.status, RouteStatus::kOk);
  // The last leg stops within one cell of the asked length.
  EXPECT_NEAR(route.length_m, options.length_m, 2.0);
  EXPECT_NEAR(route.length_m, polylineLength(route.waypoints), 1e-9);
  // Cells on the path keep min_clearance; the simplified polyline departs from
  // them by at most the simplify tolerance plus half a cell diagonal.
  const double allowed = options.min_clearance_m - options.simplify_tolerance_m - 0.36;
  double min_clearance = 1e9;
  for (size_t i = 1; i < route.waypoints.size(); ++i) {
    const Eigen::Vector2d& a = route.waypoints[i - 1];
    const Eigen::Vector2d& b = route.waypoints[i];
    for (double s = 0.0; s <= 1.0; s += 0.1 / (b - a).norm()) {
      min_clearance = std::min(min_clearance, map.clearanceAt(a + s * (b - a)));
    }
  }
  EXPECT_GE(min_clearance, allowed);
  // On the street centre line of a 14 m street the clearance is 7 m.
  EXPECT_LT(min_clearance, 7.5);
}

TEST(StreetRoute, SameSeedSameRouteOtherSeedOtherRoute) {
  const OccupancyMap map(makeBoxCity(3, 14.0), 0.5);
  StreetRouteOptions options;
  const StreetRoute a = planStreetRoute(map, options);
  const StreetRoute b = planStreetRoute(map, options);
  options.seed = 2;
  const StreetRoute c = planStreetRoute(map, options);
  ASSERT_EQ(a.waypoints.size(), b.waypoints.size());
  for (size_t i = 0; i < a.waypoints.size(); ++i) {
    EXPECT_EQ(a.waypoints[i], b.waypoints[i]);
  }
  EXPECT_NE(a.waypoints.front(), c.waypoints.front());
}

TEST(StreetRoute, ReportsStreetsTooNarrowForTheClearance) {
  // 3 m streets plus 1 m gaps: at most 2 m to a façade, 2.9 m at crossings.
  const OccupancyMap map(makeBoxCity(2, 3.0), 0.5, 0.0);
  StreetRouteOptions options;
  options.min_clearance_m = 3.0;
  EXPECT_EQ(planStreetRoute(map, options).status, RouteStatus::kNoStreets);
}

TEST(StreetRoute, ReportsANetworkTooSmallForTheLength) {
  const OccupancyMap map(makeBoxCity(2, 10.0), 0.5, 0.0);
  StreetRouteOptions options;
  options.length_m = 5000.0;
  options.max_legs = 3;
  const StreetRoute route = planStreetRoute(map, options);
  EXPECT_EQ(route.status, RouteStatus::kTooShort);
  EXPECT_GT(route.length_m, 0.0);
}

}  // namespace
}  // namespace lineloc
