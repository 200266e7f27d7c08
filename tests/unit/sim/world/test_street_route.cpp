#include <gtest/gtest.h>

#include <set>

#include "sim/world/route_trajectory.h"
#include "sim/world/street_route.h"
#include "tests/unit/sim/world/box_city.h"
#include "tests/unit/sim/world/shared_city.h"
#include "tests/unit/sim/world/street_layouts.h"

namespace lineloc {
namespace {

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

// Where a route turns back: the points p(s + 10 m) for s at which it heads
// the other way 20 m on (the directions at s and s + 20 m, taken over 1 m, at more than
// 155 degrees), the first of every 25 m. A turn at a junction is at most 90
// degrees, two in a row are a block apart; a turn back is 18 m long.
std::vector<Eigen::Vector2d> turnsBack(const std::vector<Eigen::Vector2d>& route) {
  const double length_m = polylineLength(route);
  const auto direction = [&](double s) {
    return (pointAlong(route, s + 1.0) - pointAlong(route, s)).normalized();
  };
  std::vector<Eigen::Vector2d> turns;
  for (double s = 0.0; s + 21.0 <= length_m; s += 1.0) {
    if (direction(s).dot(direction(s + 20.0)) < -0.9) {
      turns.push_back(pointAlong(route, s + 10.0));
      s += 25.0;
    }
  }
  return turns;
}

double distanceToNearestDeadEnd(const StreetNetwork& network, const Eigen::Vector2d& xy) {
  double nearest_m = std::numeric_limits<double>::infinity();
  for (const StreetNetwork::Node& node : network.nodes) {
    if (node.degree() == 1) {
      nearest_m = std::min(nearest_m, (node.xy - xy).norm());
    }
  }
  return nearest_m;
}

double leastClearanceAlong(const OccupancyMap& map, const std::vector<Eigen::Vector2d>& route) {
  double least_m = std::numeric_limits<double>::infinity();
  for (double s = 0.0; s <= polylineLength(route); s += 0.1) {
    least_m = std::min(least_m, map.clearanceAt(pointAlong(route, s)));
  }
  return least_m;
}

TEST(StreetRoute, DrivesManyStreetsOfAGridCityTurningBackOnlyAtDeadEnds) {
  const OccupancyMap map(makeBoxCity(4, 14.0), 0.5);
  const StreetNetworkOptions network_options;
  const StreetNetwork network = buildStreetNetwork(map, network_options);
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    StreetRouteOptions options;
    options.length_m = 1500.0;
    options.seed = seed;
    const StreetRoute route = planStreetRoute(network, map, options);
    ASSERT_EQ(route.status, RouteStatus::kOk) << "seed " << seed;
    EXPECT_NEAR(route.length_m, options.length_m, 1e-6);
    EXPECT_NEAR(route.length_m, polylineLength(route.waypoints), 1e-9);
    const std::set<int> edges(route.edges.begin(), route.edges.end());
    EXPECT_GE(edges.size(), 15u) << "seed " << seed;
    // An edge that follows itself is a turn back; its far end is a dead end.
    for (size_t i = 1; i < route.edges.size(); ++i) {
      if (route.edges[i] == route.edges[i - 1]) {
        const StreetNetwork::Edge& edge = network.edges[route.edges[i]];
        EXPECT_TRUE(network.nodes[edge.from].degree() == 1 || network.nodes[edge.to].degree() == 1)
            << "seed " << seed << ": turned back on edge " << route.edges[i];
      }
    }
    // The route's geometry: the dead ends lie 47 m from the outer crossings;
    // the robot turns back before it would look out of the city.
    const std::vector<Eigen::Vector2d> turns = turnsBack(route.waypoints);
    EXPECT_GE(turns.size(), 2u) << "seed " << seed;
    for (const Eigen::Vector2d& turn : turns) {
      EXPECT_LT(distanceToNearestDeadEnd(network, turn), 40.0)
          << "seed " << seed << ": turns back at " << turn.transpose();
    }
    // The centre lines of 14 m streets keep 7 m from the façades, the turns
    // back (3 m to either side) 4 m.
    EXPECT_GE(leastClearanceAlong(map, route.waypoints), network_options.min_clearance_m)
        << "seed " << seed;
  }
}

TEST(StreetRoute, SameSeedSameRouteOtherSeedOtherRoute) {
  const OccupancyMap map(makeBoxCity(3, 14.0), 0.5);
  const StreetNetwork network = buildStreetNetwork(map, StreetNetworkOptions{});
  StreetRouteOptions options;
  options.length_m = 400.0;
  const StreetRoute a = planStreetRoute(network, map, options);
  const StreetRoute b = planStreetRoute(network, map, options);
  options.seed = 2;
  const StreetRoute c = planStreetRoute(network, map, options);
  EXPECT_EQ(a.waypoints, b.waypoints);
  EXPECT_EQ(a.edges, b.edges);
  EXPECT_NE(a.waypoints.front(), c.waypoints.front());
}

TEST(StreetRoute, TurnsBackAtTheEndOfACulDeSac) {
  const OccupancyMap map(makeCulDeSacCity(), 0.5);
  const StreetNetwork network = buildStreetNetwork(map, StreetNetworkOptions{});
  int entered = 0;
  for (uint32_t seed = 1; seed <= 10; ++seed) {
    StreetRouteOptions options;
    options.length_m = 600.0;
    options.seed = seed;
    const StreetRoute route = planStreetRoute(network, map, options);
    ASSERT_EQ(route.status, RouteStatus::kOk);
    // The drive from its first time on the main street (it may start in the
    // cul-de-sac).
    const auto on_main_street =
        std::find_if(route.waypoints.begin(), route.waypoints.end(),
                     [](const Eigen::Vector2d& xy) { return xy.y() < 5.0; });
    const std::vector<Eigen::Vector2d> drive(on_main_street, route.waypoints.end());
    double furthest_y = -1e9;
    for (const Eigen::Vector2d& xy : drive) {
      furthest_y = std::max(furthest_y, xy.y());
    }
    if (furthest_y < 20.0) {
      continue;  // never took the cul-de-sac
    }
    ++entered;
    // A 3 m turn keeping 1.5 m from the closing façade (on cells of 0.5 m)
    // reaches to within 2 m of it.
    EXPECT_GT(furthest_y, kCulDeSacEndY_m - 4.0) << "seed " << seed;
    const std::vector<Eigen::Vector2d> turns = turnsBack(drive);
    EXPECT_TRUE(
        std::any_of(turns.begin(), turns.end(),
                    [](const Eigen::Vector2d& xy) { return xy.y() > kCulDeSacEndY_m - 15.0; }))
        << "seed " << seed << ": no turn back at the end of the cul-de-sac";
    EXPECT_GE(leastClearanceAlong(map, route.waypoints), StreetRouteOptions{}.min_turn_clearance_m);
  }
  EXPECT_GE(entered, 5);
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

TEST(StreetRoute, TurnsBackBeforeLookingOutOfAStreetThatEndsInOpenLand) {
  // Looking along the street, the façades fill half of a 60 degree view up to
  // 22 m before the buildings end (at x = 1 and 59): the turns back keep them
  // in view, and nothing of the route crosses the open land.
  const OccupancyMap map(makeTwoStreets(), 0.5, 10.0);
  const StreetNetwork network = buildStreetNetwork(map, StreetNetworkOptions{});
  const auto in_a_street = [](const Eigen::Vector2d& xy) {
    return std::abs(xy.y()) < 6.0 &&
           ((xy.x() > 1.0 && xy.x() < 59.0) || (xy.x() > 161.0 && xy.x() < 219.0));
  };
  for (uint32_t seed = 1; seed <= 10; ++seed) {
    StreetRouteOptions options;
    options.length_m = 150.0;
    options.seed = seed;
    const StreetRoute route = planStreetRoute(network, map, options);
    ASSERT_EQ(route.status, RouteStatus::kOk) << "seed " << seed;
    EXPECT_GE(turnsBack(route.waypoints).size(), 2u) << "seed " << seed;
    for (double along_m = 0.0; along_m <= route.length_m; along_m += 0.5) {
      const Eigen::Vector2d xy = pointAlong(route.waypoints, along_m);
      EXPECT_TRUE(in_a_street(xy))
          << "seed " << seed << ": " << along_m << " m along, at " << xy.transpose();
      EXPECT_TRUE(xy.x() < 45.0 || (xy.x() > 175.0 && xy.x() < 205.0))
          << "seed " << seed << ": " << along_m << " m along, at " << xy.transpose()
          << ", looking out of the street";
    }
  }
}

TEST(StreetRoute, ReportsANetworkWithoutStreets) {
  const OccupancyMap map(makeBoxCity(2, 3.0), 0.5, 0.0);
  EXPECT_EQ(
      planStreetRoute(buildStreetNetwork(map, StreetNetworkOptions{}), map, StreetRouteOptions{})
          .status,
      RouteStatus::kNoStreets);
}

TEST(StreetRoute, DelftDriveTurnsBackAtBothEndsOfItsStreet) {
  const OccupancyMap map = bundledDelftMap();
  const StreetNetwork network = buildStreetNetwork(map, StreetNetworkOptions{});
  StreetRouteOptions options;
  options.length_m = 1000.0;
  const StreetRoute route = planStreetRoute(network, map, options);
  ASSERT_EQ(route.status, RouteStatus::kOk);
  const std::vector<Eigen::Vector2d> turns = turnsBack(route.waypoints);
  ASSERT_GE(turns.size(), 2u);
  // The street runs 100 m between its dead ends, where it opens onto land
  // the model does not hold: every turn back is near one of them, each at the
  // other end from the one before.
  for (size_t i = 0; i < turns.size(); ++i) {
    EXPECT_LT(distanceToNearestDeadEnd(network, turns[i]), 25.0) << "at " << turns[i].transpose();
    if (i > 0) {
      EXPECT_GT((turns[i] - turns[i - 1]).norm(), 50.0) << "at " << turns[i].transpose();
    }
  }
}

}  // namespace
}  // namespace lineloc
