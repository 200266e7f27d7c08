// Tile queries against a real PostGIS database holding cubes of known geometry.
#include <gtest/gtest.h>

#include "db/enrichment_store.h"
#include "db/tiles/map_tile_query.h"
#include "tests/support/test_database.h"

namespace lineloc::db {
namespace {

TEST(MapTileQuery, ReturnsTheLinesOfTheCubesMeetingTheSquareInWorldCoordinates) {
  test::TestDatabase database("tile_query");
  test::insertCubeBuilding(database.conninfo(), 85000, 447000, 0, 0);
  test::insertCubeBuilding(database.conninfo(), 85000, 447000, 300, 0);
  Connection connection(database.conninfo(test::DatabaseRole::kReader));
  MapTileQuery query(connection, *findSite(connection, "test"));

  const TileContents first = query.within({Eigen::Vector2d(-50, -50), Eigen::Vector2d(50, 50)});
  EXPECT_EQ(first.lines.size(), 12u);
  for (const ModelLine& line : first.lines) {
    EXPECT_TRUE((line.start_world.array() >= -1e-9).all() &&
                (line.start_world.array() <= 10 + 1e-9).all());
  }
  // A square touching only the second cube's west wall (x = 300) brings the
  // whole building: tiles carry buildings, not cut pieces of them.
  EXPECT_EQ(query.within({Eigen::Vector2d(250, 0), Eigen::Vector2d(300, 5)}).lines.size(), 12u);
  EXPECT_EQ(query.within({Eigen::Vector2d(100, 100), Eigen::Vector2d(200, 200)}).lines.size(), 0u);
  EXPECT_EQ(query.within({Eigen::Vector2d(-10, -10), Eigen::Vector2d(400, 20)}).lines.size(), 24u);
  MapTileQuery second(connection, *findSite(connection, "test"));
  EXPECT_EQ(second.within({Eigen::Vector2d(-50, -50), Eigen::Vector2d(50, 50)}).lines.size(), 12u);
}

TEST(MapTileQuery, DecodesFacesAsOpenRings) {
  test::TestDatabase database("tile_faces");
  Connection connection(database.conninfo());
  const Site site = ensureSite(connection, "faces", 7415, {85000, 447000, 0});
  const std::string building =
      connection
          .execParams(
              "INSERT INTO building (site_id, source, source_id) VALUES ($1, 't', 'b') "
              "RETURNING id",
              {std::to_string(site.id)})
          .text(0, 0);
  connection.execParams(
      "INSERT INTO face (site_id, building_id, kind, geom) VALUES ($1, $2, 1, "
      "ST_GeomFromText('POLYGON Z ((85000 447000 0, 85010 447000 0, 85010 447000 8, "
      "85000 447000 8, 85000 447000 0))', 7415))",
      {std::to_string(site.id), building});
  MapTileQuery query(connection, site);
  const TileContents tile = query.within({Eigen::Vector2d(-5, -5), Eigen::Vector2d(5, 5)});
  ASSERT_EQ(tile.faces.size(), 1u);
  EXPECT_EQ(tile.faces[0].kind, 1);
  ASSERT_EQ(tile.faces[0].ring_world.size(), 4u);
  EXPECT_TRUE(tile.faces[0].ring_world[2].isApprox(Eigen::Vector3d(10, 0, 8)));
}

TEST(MapTileQuery, HoldsTheConfirmedLearntLinesMeetingTheSquareWhenAsked) {
  test::TestDatabase database("tile_learnt");
  test::insertCubeBuilding(database.conninfo(), 85000, 447000, 0, 0);
  Connection enricher(database.conninfo(test::DatabaseRole::kEnricher));
  const Site site = *findSite(enricher, "test");
  const auto sighting = [](double height_m, double sigma_m) {
    EnrichmentSighting line;
    line.start_world = {2.0, 0.0, height_m};
    line.end_world = {4.0, 0.0, height_m};
    line.start_covariance = Eigen::Matrix3d::Identity() * 1e-6;
    line.end_covariance = Eigen::Vector3d(1e-6, 1e-6, sigma_m * sigma_m).asDiagonal();
    line.plane_normal = -Eigen::Vector3d::UnitY();
    line.plane_offset = 0.0;
    line.robot = "r1";
    line.views = 4;
    return line;
  };
  // Two lines seen on two passes, one on the first only.
  writeEnrichmentPass(enricher, site, "monday", {sighting(3.0, 0.02), sighting(6.0, 0.01)});
  writeEnrichmentPass(enricher, site, "tuesday", {sighting(3.0, 0.02)});
  Connection reader(database.conninfo(test::DatabaseRole::kReader));
  const Eigen::AlignedBox2d around(Eigen::Vector2d(-50, -50), Eigen::Vector2d(50, 50));
  EXPECT_TRUE(MapTileQuery(reader, site).within(around).learnt_lines.empty());
  MapTileQuery with_learnt(reader, site, true);
  const TileContents contents = with_learnt.within(around);
  EXPECT_EQ(contents.lines.size(), 12u);
  ASSERT_EQ(contents.learnt_lines.size(), 1u);
  EXPECT_LT((contents.learnt_lines[0].start_world - Eigen::Vector3d(2, 0, 3)).norm(), 1e-9);
  EXPECT_NEAR(contents.learnt_lines[0].sigma_m, 0.02, 1e-12);
  EXPECT_TRUE(with_learnt.within({Eigen::Vector2d(100, 100), Eigen::Vector2d(200, 200)})
                  .learnt_lines.empty());
}

}  // namespace
}  // namespace lineloc::db
