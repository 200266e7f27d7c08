#include <gtest/gtest.h>

#include "common/geometry/line_segments.h"
#include "sim/world/street_clutter.h"
#include "sim/world/street_route.h"
#include "tests/unit/sim/world/box_city.h"

namespace lineloc {
namespace {

TEST(StreetClutter, PlacesObjectsBesideTheRouteNotOnItNorInBuildings) {
  const SceneMesh city = makeBoxCity(3, 16.0);
  const OccupancyMap map(city, 0.5);
  StreetRouteOptions route_options;
  route_options.length_m = 250.0;
  const StreetRoute route =
      planStreetRoute(buildStreetNetwork(map, StreetNetworkOptions{}), map, route_options);
  ASSERT_EQ(route.status, RouteStatus::kOk);
  StreetClutterOptions options;
  options.route_keep_out_m = 3.0;
  SceneMesh clutter;
  // A street climbing 2 % eastwards.
  const auto ground_height_m = [](const Eigen::Vector2d& xy) { return 1.0 + 0.02 * xy.x(); };
  const StreetClutterCounts counts =
      addStreetClutter(map, route.waypoints, ground_height_m, options, 1000, clutter);
  EXPECT_GT(counts.cars, 5);
  EXPECT_GT(counts.trees, 2);
  EXPECT_GT(counts.poles, 3);
  EXPECT_GT(counts.pedestrians, 3);
  ASSERT_GT(clutter.triangleCount(), 0u);
  for (size_t i = 0; i < clutter.triangleCount(); ++i) {
    EXPECT_GE(clutter.tag(i).object_id, 1000u);
    EXPECT_NE(clutter.tag(i).kind, SurfaceKind::kWall);
  }
  for (size_t i = 0; i < clutter.vertices().size(); ++i) {
    const Eigen::Vector3f& vertex = clutter.vertices()[i];
    const Eigen::Vector2d xy = vertex.head<2>().cast<double>();
    // An object's centre keeps route_keep_out; below the crowns (which may
    // overhang the street above the camera) its farthest vertex is at most
    // 2.3 m (half a car's diagonal) from it.
    if (clutter.tag(i / 3).kind != SurfaceKind::kFoliage) {
      EXPECT_GE(distanceToPolyline(xy, route.waypoints), options.route_keep_out_m - 2.3);
    }
    EXPECT_GT(map.clearanceAt(xy), 0.0) << "clutter inside a building at " << xy.transpose();
    // Every object stands on the ground at its centre, at most 2.3 m away.
    EXPECT_GE(vertex.z(), ground_height_m(xy) - 0.02 * 2.3 - 1e-4);
  }
}

TEST(StreetClutter, SameSeedSameScene) {
  const OccupancyMap map(makeBoxCity(2, 16.0), 0.5);
  const StreetRoute route =
      planStreetRoute(buildStreetNetwork(map, StreetNetworkOptions{}), map, StreetRouteOptions{});
  SceneMesh a;
  SceneMesh b;
  const auto flat = [](const Eigen::Vector2d&) { return 0.0; };
  addStreetClutter(map, route.waypoints, flat, StreetClutterOptions{}, 1, a);
  addStreetClutter(map, route.waypoints, flat, StreetClutterOptions{}, 1, b);
  ASSERT_EQ(a.vertices().size(), b.vertices().size());
  EXPECT_TRUE(std::equal(a.vertices().begin(), a.vertices().end(), b.vertices().begin()));
}

}  // namespace
}  // namespace lineloc
