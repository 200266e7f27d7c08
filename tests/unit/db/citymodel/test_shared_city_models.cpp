// The city-model readers on the real files of ../shared/data: every building
// and face at the highest level of detail (counts computed independently in
// tests/unit/db/independent_counts.h), the objects they skip, the LoD option,
// and Den Haag's whole tile with its terrain.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "db/citymodel/cityjson_reader.h"
#include "tests/unit/db/independent_counts.h"

namespace lineloc::citymodel {
namespace {

struct RealFile {
  std::string name;
  std::string highest_lod;  // read from the files by hand (README and a look at each)
  std::optional<int> epsg;
};

class RealCityModels : public ::testing::TestWithParam<RealFile> {};

TEST_P(RealCityModels, LoadAllBuildingsAndFacesAtTheHighestLod) {
  const RealFile& file = GetParam();
  const std::string text = test::readSharedCityModel(file.name);
  const CityModel model = file.name.ends_with(".jsonl") ? readCityJsonLines(text, file.name, {})
                                                        : readCityJson(text, file.name, {});
  const test::CityModelCounts expected = test::countCityModel(file.name, file.highest_lod);
  EXPECT_EQ(model.epsg, file.epsg);
  EXPECT_EQ(static_cast<int>(model.buildings.size()), expected.buildings);
  int faces = 0;
  for (const Building& building : model.buildings) {
    faces += static_cast<int>(building.faces.size());
    if (!building.faces.empty()) {
      EXPECT_EQ(building.lod, file.highest_lod);
    }
  }
  EXPECT_EQ(faces, expected.faces);
}

INSTANTIATE_TEST_SUITE_P(SharedData, RealCityModels,
                         ::testing::Values(RealFile{"delft.json", "1", 7415},
                                           RealFile{"delft_1b.json", "1", 7415},
                                           RealFile{"DH_01_subs.city.json", "2", std::nullopt},
                                           RealFile{"multi_lod.json", "2.2", std::nullopt},
                                           RealFile{"503100000000296.city.jsonl", "2.2", 7415}),
                         [](const auto& info) { return "file" + std::to_string(info.index); });

TEST(CityJsonReader, DelftSkipsTheNonBuildingObjectsByType) {
  const CityModel model = readCityJson(test::readSharedCityModel("delft.json"), "delft.json", {});
  // README: 143 roads, 126 plant covers, 81 land-use areas, 3 bridges, and the
  // file also holds 54 generic objects and 3 water bodies: 410 in all.
  EXPECT_EQ(model.skipped.total(), 410);
  EXPECT_EQ(model.skipped.count_by_reason.at("not a building (Road)"), 143);
}

TEST(CityJsonReader, LodOptionPicksALevelAndRefusesAMissingOne) {
  const std::string text = test::readSharedCityModel("multi_lod.json");
  const CityModel lod12 = readCityJson(text, "multi_lod.json", {.lod = "1.2"});
  ASSERT_FALSE(lod12.buildings.empty());
  EXPECT_EQ(lod12.buildings.front().lod, "1.2");
  EXPECT_EQ(readCityJson(text, "multi_lod.json", {.lod = "2"}).buildings.front().lod, "2.2");
  EXPECT_THROW(readCityJson(text, "multi_lod.json", {.lod = "3"}), ModelError);
}

TEST(CityJsonReader, DenHaagKeepsEveryBuildingAndItsWholeTerrain) {
  const std::string name = "denhaag_01.city.json";
  const std::string text = test::readSharedCityModel(name);
  const CityModel model = readCityJson(text, name, {});
  EXPECT_EQ(static_cast<int>(model.buildings.size()), test::countCityModel(name, "2").buildings);
  // Independently: each TINRelief surface's exterior ring of n vertices holds
  // n - 2 triangles.
  const nlohmann::json document = nlohmann::json::parse(text);
  size_t triangles = 0;
  for (const auto& [id, object] : document["CityObjects"].items()) {
    if (object["type"] == "TINRelief") {
      for (const nlohmann::json& surface : object["geometry"][0]["boundaries"]) {
        triangles += surface[0].size() - 2;
      }
    }
  }
  EXPECT_GT(triangles, 5000u);
  EXPECT_EQ(model.terrain.size(), triangles);
}

}  // namespace
}  // namespace lineloc::citymodel
