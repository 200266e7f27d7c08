// The real city models of ../shared/data loaded into a real PostGIS server,
// with counts computed independently from the files: the five small models,
// and Den Haag's whole tile with its terrain, which the tile query hands back.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "db/loader/loader.h"
#include "db/site.h"
#include "db/tiles/map_tile_query.h"
#include "tests/support/test_database.h"
#include "tests/unit/db/independent_counts.h"

namespace lineloc::db {
namespace {

int count(Connection& connection, const std::string& sql) {
  return std::stoi(connection.exec(sql).text(0, 0));
}

struct SharedFile {
  std::string name;
  std::string lod;
  bool names_crs;
};

const std::vector<SharedFile> kSharedFiles = {{"delft.json", "1", true},
                                              {"delft_1b.json", "1", true},
                                              {"DH_01_subs.city.json", "2", false},
                                              {"multi_lod.json", "2.2", false},
                                              {"503100000000296.city.jsonl", "2.2", true}};

TEST(Loader, AllFiveSharedFilesLoadWithTheirIndependentCounts) {
  test::TestDatabase database("loader_shared");
  Connection connection(database.conninfo());
  LoadOptions options;
  options.site = "delft";
  for (const SharedFile& file : kSharedFiles) {
    const std::string path = test::sharedCityModelPath(file.name);
    if (!file.names_crs) {
      try {
        loadFile(path, options, &connection, nullptr);
        FAIL() << file.name << " names no CRS and must be refused without --crs";
      } catch (const citymodel::ModelError& error) {
        EXPECT_EQ(error.reason(), "no CRS");
        EXPECT_NE(std::string(error.what()).find(file.name), std::string::npos);
      }
    }
    LoadOptions with_crs = options;
    with_crs.file_epsg = 7415;
    const LoadReport report =
        loadFile(path, file.names_crs ? options : with_crs, &connection, nullptr);
    const test::CityModelCounts expected = test::countCityModel(file.name, file.lod);
    const std::string where = fmt::format("WHERE source = '{}'", file.name);
    EXPECT_EQ(count(connection, "SELECT count(*) FROM building " + where), expected.buildings)
        << file.name;
    EXPECT_EQ(count(connection,
                    "SELECT count(*) FROM face JOIN building b ON b.id = building_id " + where),
              expected.faces - expected.collapsed_faces)
        << file.name;
    EXPECT_EQ(report.lod, file.lod);
    EXPECT_GT(count(connection,
                    "SELECT count(*) FROM line JOIN building b ON b.id = building_id " + where),
              0);
  }
  // BuildingParts point at their Building: DH_01 has 8 parts, the 3D BAG file 1.
  EXPECT_EQ(count(connection, "SELECT count(*) FROM building WHERE parent_id IS NOT NULL"), 9);
  EXPECT_EQ(count(connection, "SELECT count(*) FROM source_file"), 5);
}

TEST(Loader, DenHaagLoadsWholeWithItsTerrainWithoutSkippingAnything) {
  test::TestDatabase database("loader_denhaag");
  Connection connection(database.conninfo());
  LoadOptions options;
  options.site = "denhaag";
  const std::string name = "denhaag_01.city.json";
  const LoadReport report =
      loadFile(test::sharedCityModelPath(name), options, &connection, nullptr);
  EXPECT_EQ(report.buildings, test::countCityModel(name, "2").buildings);
  EXPECT_EQ(count(connection, "SELECT count(*) FROM building"), report.buildings);
  EXPECT_GT(report.skipped.count_by_reason.at("non-planar face triangulated"), 0);
  EXPECT_EQ(report.skipped.count_by_reason.count("non-planar polygon"), 0u);
  EXPECT_GT(report.terrain_triangles, 5000);
  EXPECT_EQ(count(connection, "SELECT count(*) FROM terrain_triangle"), report.terrain_triangles);
  EXPECT_EQ(count(connection, "SELECT terrain_triangles FROM source_file"),
            report.terrain_triangles);

  // The tile query hands the triangles under a square back in the world frame,
  // each one whose ground projection meets it.
  const Site site = *findSite(connection, "denhaag");
  MapTileQuery query(connection, site);
  const Eigen::AlignedBox2d square(Eigen::Vector2d(-20, -20), Eigen::Vector2d(20, 20));
  const TileContents tile = query.within(square);
  ASSERT_FALSE(tile.terrain.empty());
  for (const TerrainTriangleRecord& triangle : tile.terrain) {
    Eigen::AlignedBox2d box;
    for (const Eigen::Vector3d& corner : triangle.corners_world) {
      box.extend(corner.head<2>());
      EXPECT_GT(corner.z() + site.origin.z(), 2.0) << "NAP heights of the Den Haag terrain";
      EXPECT_LT(corner.z() + site.origin.z(), 16.5);
    }
    EXPECT_TRUE(box.intersects(square));
  }

  // Reloading a changed version replaces the terrain, never adds to it.
  LoadOptions tighter = options;
  tighter.validation.planarity_tolerance_m = 0.04;
  loadFile(test::sharedCityModelPath(name), tighter, &connection, nullptr);
  EXPECT_EQ(count(connection, "SELECT count(*) FROM terrain_triangle"), report.terrain_triangles);
}

}  // namespace
}  // namespace lineloc::db
