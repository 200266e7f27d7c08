#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "sim/world/city_mesh.h"
#include "sim/world/occupancy_map.h"

namespace lineloc {
namespace {

TEST(CityMesh, ASiteOriginIsTheOneGivenOrTheDefault) {
  const std::filesystem::path path =
      std::filesystem::path(LINELOC_SOURCE_DIR) / "data" / "citymodels" / "delft.json";
  const citymodel::CityModel model = readCityModelFile(path.string());
  EXPECT_EQ(siteOriginOf(model, {}), defaultSiteOrigin(model));
  EXPECT_EQ(siteOriginOf(model, {84900.0, 447600.0, 1.0}), Eigen::Vector3d(84900.0, 447600.0, 1.0));
  EXPECT_THROW(siteOriginOf(model, {84900.0, 447600.0}), std::invalid_argument);
}

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

TEST(CityMesh, RejectsAnEmptyModel) {
  EXPECT_THROW(buildCityMesh(citymodel::CityModel{}, Eigen::Vector3d::Zero()),
               std::invalid_argument);
  EXPECT_THROW(readCityModelFile("no_such_city.json"), std::runtime_error);
}

TEST(CityMesh, ACityModelNestedTooDeeplyIsRefusedNamingTheFile) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("depth_bomb_" + std::to_string(getpid()) + ".json");
  std::ofstream(path) << R"({"type":"CityJSON","version":"2.0","CityObjects":{"b":{"type":)"
                      << R"("Building","attributes":{"a":)" << std::string(70000, '[')
                      << std::string(70000, ']') << R"(}}},"vertices":[]})";
  try {
    readCityModelFile(path.string());
    ADD_FAILURE() << "expected an error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(path.string() + ": JSON nested too deeply"),
              std::string::npos)
        << error.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace lineloc
