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
  // The searched path stops within one cell of the asked length; its
  // waypoints cut its corners, by a few metres over a turn back.
  EXPECT_LE(route.length_m, options.length_m + 0.5);
  EXPECT_GE(route.length_m, options.length_m - 8.0);
  EXPECT_NEAR(route.length_m, polylineLength(route.waypoints), 1e-9);
  // Cells on the path keep min_clearance (a turn back's, min_turn_clearance_m,
  // which a 3 m turn on these 14 m streets stays well clear of); the
  // simplified polyline departs from them by at most the simplify tolerance
  // plus half a cell diagonal.
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

// Two 12 m streets meeting in an L, lined by 18 m square buildings on both
// sides: x along y = 25 and y along x = 25. Inside the L lies open land.
SceneMesh makeLCity() {
  SceneMesh mesh;
  uint32_t id = 1;
  const auto add = [&](double x, double y) {
    mesh.addBox(Eigen::Isometry3d(Eigen::Translation3d(x, y, 5.0)), Eigen::Vector3d(9.0, 9.0, 5.0),
                SurfaceTag{SurfaceKind::kWall, id++, 0.0f, 10.0f});
  };
  for (double along = 40.0; along <= 200.0; along += 20.0) {
    add(along, 10.0);  // outer side of the x street
    add(along, 40.0);  // inner side
    add(10.0, along);  // outer side of the y street
    if (along > 40.0) {
      add(40.0, along);  // inner side; the corner building is the x street's
    }
  }
  add(10.0, 10.0);
  return mesh;
}

TEST(StreetRoute, StartsOnAStreetNotOnTheOpenLand) {
  const OccupancyMap map(makeLCity(), 0.5, 10.0);
  // Every start must lie in one of the two streets.
  const auto on_street = [](const Eigen::Vector2d& xy) {
    return (xy.y() > 19.0 && xy.y() < 31.0) || (xy.x() > 19.0 && xy.x() < 31.0);
  };
  for (uint32_t seed = 1; seed <= 10; ++seed) {
    StreetRouteOptions options;
    options.length_m = 60.0;
    options.seed = seed;
    const StreetRoute route = planStreetRoute(map, options);
    ASSERT_EQ(route.status, RouteStatus::kOk);
    const Eigen::Vector2d start = route.waypoints[0];
    EXPECT_TRUE(on_street(start)) << "seed " << seed << ": starts at " << start.transpose();
  }
}

// Two short streets 100 m apart on open land, each between two rows of three
// 18 m buildings: x in [0, 60] and [160, 220], along y = 0, 12 m wide.
SceneMesh makeTwoStreets() {
  SceneMesh mesh;
  uint32_t id = 1;
  for (const double street_x : {0.0, 160.0}) {
    for (int k = 0; k < 3; ++k) {
      for (const double side_y : {-15.0, 15.0}) {
        mesh.addBox(
            Eigen::Isometry3d(Eigen::Translation3d(street_x + 10.0 + 20.0 * k, side_y, 5.0)),
            Eigen::Vector3d(9.0, 9.0, 5.0), SurfaceTag{SurfaceKind::kWall, id++, 0.0f, 10.0f});
      }
    }
  }
  return mesh;
}

// The point `distance_m` along a polyline.
Eigen::Vector2d pointAlong(const std::vector<Eigen::Vector2d>& polyline, double distance_m) {
  for (size_t i = 1; i < polyline.size(); ++i) {
    const double length = (polyline[i] - polyline[i - 1]).norm();
    if (distance_m <= length) {
      return polyline[i - 1] + distance_m / length * (polyline[i] - polyline[i - 1]);
    }
    distance_m -= length;
  }
  return polyline.back();
}

TEST(StreetRoute, StartsLookingAlongAStreetNotOutOfIt) {
  // A leg from one street to the other runs over the open land; a start that
  // took one would show the camera nothing for its first 40 m.
  const OccupancyMap map(makeTwoStreets(), 0.5, 10.0);
  const auto in_a_street = [](const Eigen::Vector2d& xy) {
    return std::abs(xy.y()) < 6.0 &&
           ((xy.x() > 0.0 && xy.x() < 60.0) || (xy.x() > 160.0 && xy.x() < 220.0));
  };
  for (uint32_t seed = 1; seed <= 20; ++seed) {
    StreetRouteOptions options;
    options.length_m = 30.0;
    options.seed = seed;
    const StreetRoute route = planStreetRoute(map, options);
    ASSERT_FALSE(route.waypoints.empty());
    const Eigen::Vector2d ahead = pointAlong(route.waypoints, 10.0);
    EXPECT_TRUE(in_a_street(ahead))
        << "seed " << seed << ": from " << route.waypoints.front().transpose() << " heads for "
        << ahead.transpose();
  }
}

// Every metre of a route planned for `length_m` in makeTwoStreets lies in one
// of the two streets (to within the simplification's tolerance).
void expectRoutesInTheTwoStreets(double length_m) {
  const OccupancyMap map(makeTwoStreets(), 0.5, 10.0);
  const auto in_a_street = [](const Eigen::Vector2d& xy) {
    return std::abs(xy.y()) < 6.0 &&
           ((xy.x() > -1.0 && xy.x() < 61.0) || (xy.x() > 159.0 && xy.x() < 221.0));
  };
  for (uint32_t seed = 1; seed <= 20; ++seed) {
    StreetRouteOptions options;
    options.length_m = length_m;
    options.min_leg_m = 20.0;
    options.seed = seed;
    const StreetRoute route = planStreetRoute(map, options);
    ASSERT_EQ(route.status, RouteStatus::kOk) << "seed " << seed;
    for (double along_m = 0.0; along_m <= route.length_m; along_m += 1.0) {
      EXPECT_TRUE(in_a_street(pointAlong(route.waypoints, along_m)))
          << "seed " << seed << ": " << along_m << " m along, at "
          << pointAlong(route.waypoints, along_m).transpose();
    }
  }
}

TEST(StreetRoute, KeepsFacadesInViewAllTheWay) {
  // 50 m of a 60 m street: a leg over the open land to the other street, or
  // out of the street's end, would show the camera nothing for metres.
  expectRoutesInTheTwoStreets(50.0);
}

TEST(StreetRoute, TurnsBackWhereTheStreetEndsInOpenLand) {
  // 150 m: onwards, every drive would have to leave its 60 m street.
  expectRoutesInTheTwoStreets(150.0);
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
