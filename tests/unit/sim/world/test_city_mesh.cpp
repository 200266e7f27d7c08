#include <gtest/gtest.h>

#include <filesystem>

#include "sim/world/city_mesh.h"
#include "sim/world/occupancy_map.h"

namespace lineloc {
namespace {

TEST(CityMesh, DelftModelBecomesASceneAroundTheSiteOrigin) {
  const std::filesystem::path path =
      std::filesystem::path(LINELOC_SOURCE_DIR) / "data" / "citymodels" / "delft.json";
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

TEST(CityMesh, RejectsAnEmptyModel) {
  EXPECT_THROW(buildCityMesh(citymodel::CityModel{}, Eigen::Vector3d::Zero()),
               std::invalid_argument);
  EXPECT_THROW(readCityModelFile("no_such_city.json"), std::runtime_error);
}

}  // namespace
}  // namespace lineloc
