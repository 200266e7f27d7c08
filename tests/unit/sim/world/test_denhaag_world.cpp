// The simulator's world in Den Haag's centre (../shared/data), a real LoD2
// tile with terrain: its scene stands on the terrain, its street network is
// connected over most of the tile, and three-minute drives cover several of
// its streets.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <set>

#include "sim/world/city_mesh.h"
#include "sim/world/route_trajectory.h"
#include "sim/world/street_route.h"
#include "tests/unit/sim/world/network_measures.h"
#include "tests/unit/sim/world/shared_city.h"

namespace lineloc {
namespace {

TEST(CityMesh, DenHaagsTerrainIsTheGroundTheSceneStandsOn) {
  const std::filesystem::path path =
      std::filesystem::path(LINELOC_SHARED_DATA_DIR) / "citymodels" / "denhaag_01.city.json";
  ASSERT_TRUE(std::filesystem::exists(path))
      << "shared data missing: " << path << " (set LINELOC_SHARED_DATA_DIR)";
  const citymodel::CityModel model = readCityModelFile(path.string());
  const Eigen::Vector3d origin(78650.0, 457950.0, 0.0);
  const CityMesh city = buildCityMesh(model, origin);
  size_t ground_triangles = 0;
  for (size_t i = 0; i < city.mesh.triangleCount(); ++i) {
    ground_triangles += city.mesh.tag(i).kind == SurfaceKind::kGround;
  }
  EXPECT_EQ(ground_triangles, model.terrain.size());
  ASSERT_FALSE(city.terrain.empty());
  // The plane lies under the terrain, which spans NAP 2.5-15.9 m.
  EXPECT_NEAR(city.ground_z_m, 2.463, 1e-3);
  for (const citymodel::TerrainTriangle& triangle : model.terrain) {
    const Eigen::Vector3d centroid = (triangle[0] + triangle[1] + triangle[2]) / 3.0 - origin;
    ASSERT_NEAR(groundHeightAt(city, centroid.head<2>()), centroid.z(), 1e-6);
  }
  EXPECT_DOUBLE_EQ(groundHeightAt(city, {5000.0, 0.0}), city.ground_z_m) << "off the terrain";
  // The occupancy map holds the buildings only, not the ground.
  const OccupancyMap map(city.mesh);
  EXPECT_LT(cv::countNonZero(map.occupied()), map.cols() * map.rows() / 2);
}

TEST(StreetNetwork, DenHaagIsConnectedOverMostOfTheModel) {
  const OccupancyMap map = sharedCityMap("denhaag_01.city.json");
  const auto start = std::chrono::steady_clock::now();
  const StreetNetwork network = buildStreetNetwork(map, StreetNetworkOptions{});
  fmt::print("Den Haag network built in {:.2f} s\n",
             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  printSize("Den Haag", network);
  EXPECT_GT(static_cast<int>(network.nodes.size()) - countDegree(network, 1), 30);
  EXPECT_GT(largestComponentShare(network), 0.7);
}

// The streets of a city model a RouteTrajectory driving a planned route with
// default speeds passes in `duration_s`: the edges within 2 m of its
// positions, taken every second.
std::set<int> edgesDriven(const StreetNetwork& network, const OccupancyMap& map, double duration_s,
                          uint32_t seed) {
  RouteDriveOptions drive;
  drive.duration_s = duration_s;
  drive.seed = seed;
  StreetRouteOptions options;
  options.length_m = drive.max_speed_m_s * duration_s + 20.0;
  options.seed = seed;
  const StreetRoute route = planStreetRoute(network, map, options);
  EXPECT_EQ(route.status, RouteStatus::kOk);
  const RouteTrajectory trajectory(
      route.waypoints, [](const Eigen::Vector2d&) { return 0.0; }, drive);
  std::set<int> edges;
  for (int64_t t = trajectory.startStamp_ns(); t <= trajectory.endStamp_ns(); t += 1'000'000'000) {
    const Eigen::Vector2d xy = trajectory.at(t).p_world_body.head<2>();
    for (size_t e = 0; e < network.edges.size(); ++e) {
      const std::vector<Eigen::Vector2d>& line = network.edges[e].polyline;
      for (size_t i = 1; i < line.size(); ++i) {
        const Eigen::Vector2d ab = line[i] - line[i - 1];
        const double s = std::clamp((xy - line[i - 1]).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        if ((xy - line[i - 1] - s * ab).norm() < 2.0) {
          edges.insert(static_cast<int>(e));
        }
      }
    }
  }
  return edges;
}

TEST(StreetRoute, ThreeMinutesInDenHaagDriveSeveralStreets) {
  const OccupancyMap map = sharedCityMap("denhaag_01.city.json");
  const StreetNetwork network = buildStreetNetwork(map, StreetNetworkOptions{});
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    const auto start = std::chrono::steady_clock::now();
    const std::set<int> edges = edgesDriven(network, map, 180.0, seed);
    fmt::print("Den Haag seed {}: {} streets in 180 s ({:.2f} s to plan and drive)\n", seed,
               edges.size(),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    EXPECT_GE(edges.size(), 3u) << "seed " << seed;
  }
}

}  // namespace
}  // namespace lineloc
