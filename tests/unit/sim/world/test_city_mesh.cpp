#include <gtest/gtest.h>

#include <filesystem>

#include "sim/world/city_mesh.h"
#include "sim/world/occupancy_map.h"

namespace lineloc {
namespace {

double meshArea(const std::vector<Eigen::Vector3d>& ring,
                const std::vector<std::array<int, 3>>& triangles) {
  double area = 0.0;
  for (const auto& t : triangles) {
    area += 0.5 * (ring[t[1]] - ring[t[0]]).cross(ring[t[2]] - ring[t[0]]).norm();
  }
  return area;
}

TEST(TriangulateRing, ConcaveFootprintIsCoveredExactly) {
  // An L-shaped roof at 7 m: 10 x 10 minus the 6 x 6 corner = 64 m^2.
  const std::vector<Eigen::Vector3d> ring = {{0, 0, 7}, {10, 0, 7}, {10, 4, 7},
                                             {4, 4, 7}, {4, 10, 7}, {0, 10, 7}};
  const auto triangles = triangulateRing(ring, Eigen::Vector3d::UnitZ());
  ASSERT_EQ(triangles.size(), 4u);
  EXPECT_NEAR(meshArea(ring, triangles), 64.0, 1e-9);
  for (const auto& t : triangles) {
    // Every triangle keeps the ring's orientation (normal up).
    EXPECT_GT((ring[t[1]] - ring[t[0]]).cross(ring[t[2]] - ring[t[0]]).z(), 0.0);
  }
}

TEST(TriangulateRing, VerticalWallAndClockwiseRings) {
  const std::vector<Eigen::Vector3d> wall = {{0, 0, 0}, {0, 0, 9}, {5, 0, 9}, {5, 0, 0}};
  const auto triangles = triangulateRing(wall, Eigen::Vector3d(0, 1, 0) * 90.0);
  ASSERT_EQ(triangles.size(), 2u);
  EXPECT_NEAR(meshArea(wall, triangles), 45.0, 1e-9);
}

TEST(TriangulateRing, DegenerateRingsGiveNothing) {
  EXPECT_TRUE(triangulateRing({{0, 0, 0}, {1, 0, 0}}, Eigen::Vector3d::UnitZ()).empty());
  EXPECT_TRUE(triangulateRing({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, Eigen::Vector3d::Zero()).empty());
  // Collinear points have no ear.
  EXPECT_TRUE(
      triangulateRing({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}, Eigen::Vector3d::UnitZ())
          .empty());
}

TEST(CityMesh, DelftModelBecomesASceneAroundTheSiteOrigin) {
  const std::filesystem::path path =
      std::filesystem::path(LINELOC_SHARED_DATA_DIR) / "citymodels" / "delft.json";
  ASSERT_TRUE(std::filesystem::exists(path))
      << "shared data missing: " << path << " (set LINELOC_SHARED_DATA_DIR)";
  const citymodel::CityModel model = readCityModelFile(path.string());
  const Eigen::Vector3d origin = defaultSiteOrigin(model);
  // Inside the model's extent x 84616..85141, y 447423..447751 (EPSG:7415).
  EXPECT_GT(origin.x(), 84616.0);
  EXPECT_LT(origin.x(), 85141.0);
  EXPECT_GT(origin.y(), 447423.0);
  EXPECT_LT(origin.y(), 447751.0);
  const CityMesh city = buildCityMesh(model, origin);
  Eigen::AlignedBox3f bounds;
  for (const Eigen::Vector3f& vertex : city.mesh.vertices()) {
    bounds.extend(vertex);
  }
  // The origin is the centre of the buildings' box, rounded to metres.
  EXPECT_LE(std::abs(bounds.min().x() + bounds.max().x()), 1.0f);
  EXPECT_LE(std::abs(bounds.min().y() + bounds.max().y()), 1.0f);
  EXPECT_EQ(city.building_count, 160);
  EXPECT_EQ(city.skipped_faces, 0);
  EXPECT_GT(city.mesh.triangleCount(), 3000u);
  // Street level in Delft's centre is near NAP 0 m.
  EXPECT_NEAR(city.ground_z_m, 0.0, 1.5);
  for (const Eigen::Vector3f& vertex : city.mesh.vertices()) {
    ASSERT_LT(vertex.head<2>().cwiseAbs().maxCoeff(), 300.0f);
  }
  const OccupancyMap map(city.mesh);
  EXPECT_GT(cv::countNonZero(map.occupied()), 0);
}

TEST(CityMesh, RejectsAnEmptyModel) {
  EXPECT_THROW(buildCityMesh(citymodel::CityModel{}, Eigen::Vector3d::Zero()),
               std::invalid_argument);
  EXPECT_THROW(readCityModelFile("no_such_city.json"), std::runtime_error);
}

}  // namespace
}  // namespace lineloc
