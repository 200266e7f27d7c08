// The schema, its migration runner and the map query, on a real PostGIS server.
#include <gtest/gtest.h>

#include "db/connection.h"
#include "db/migrations.h"
#include "db/model_line_query.h"
#include "db/site.h"
#include "tests/support/test_database.h"

namespace lineloc::db {
namespace {

constexpr double kOriginX = 85000.0;
constexpr double kOriginY = 447000.0;

TEST(Migrations, ApplyOnceThenNothing) {
  test::TestDatabase database("migrations");
  Connection connection(database.conninfo());
  const int newest = embeddedMigrations().back().version;
  EXPECT_EQ(schemaVersion(connection), newest);
  EXPECT_EQ(applyMigrations(connection, embeddedMigrations()), 0);
  EXPECT_EQ(schemaVersion(connection), newest);
}

TEST(Migrations, LayTheTablesInSchemaLinelocOwnedByTheOwnerRole) {
  test::TestDatabase database("migrations_schema");
  Connection connection(database.conninfo());
  EXPECT_EQ(connection
                .exec("SELECT string_agg(tablename, ',') FROM pg_tables WHERE schemaname = "
                      "'public' AND tablename <> 'spatial_ref_sys'")
                .text(0, 0),
            "");
  EXPECT_EQ(connection
                .exec("SELECT string_agg(DISTINCT tableowner, ',') || ' ' || count(*) FROM "
                      "pg_tables WHERE schemaname = 'lineloc'")
                .text(0, 0),
            "lineloc_owner 15");
  // Every role finds the tables by the database's search_path.
  Connection reader(database.conninfo(test::DatabaseRole::kReader));
  EXPECT_EQ(reader.exec("SELECT current_schemas(false)::text").text(0, 0), "{lineloc,public}");
  EXPECT_EQ(reader
                .exec("SELECT relnamespace::regnamespace::text FROM pg_class WHERE oid = "
                      "to_regclass('line')")
                .text(0, 0),
            "lineloc");
}

TEST(Migrations, RequireMigratedTellsToRunLinelocMigrate) {
  test::TestDatabase database("migrations_required");
  Connection writer(database.conninfo(test::DatabaseRole::kWriter));
  EXPECT_NO_THROW(requireMigrated(writer, embeddedMigrations()));
  std::vector<Migration> newer = embeddedMigrations();
  newer.push_back({newer.back().version + 1, "newer", "SELECT 1"});
  try {
    requireMigrated(writer, newer);
    FAIL() << "a schema behind the newest migration must be refused";
  } catch (const DatabaseError& error) {
    EXPECT_NE(std::string(error.what()).find("lineloc-migrate"), std::string::npos);
  }
  EXPECT_THROW(applyMigrations(writer, newer), DatabaseError) << "the writer may not migrate";
}

TEST(Migrations, FailingMigrationRollsBackAndNamesItself) {
  test::TestDatabase database("migration_failure");
  Connection connection(database.conninfo());
  const std::vector<Migration> broken = {
      {9001, "creates_then_fails", "CREATE TABLE half_done (x int); SELECT no_such_function();"}};
  try {
    applyMigrations(connection, broken);
    FAIL() << "a broken migration must throw";
  } catch (const DatabaseError& error) {
    EXPECT_NE(std::string(error.what()).find("9001_creates_then_fails"), std::string::npos);
  }
  EXPECT_EQ(connection.exec("SELECT to_regclass('half_done') IS NULL").text(0, 0), "t");
  EXPECT_LT(schemaVersion(connection), 9001);
}

TEST(Site, EnsureIsIdempotentAndRefusesAnotherCrs) {
  test::TestDatabase database("site");
  Connection connection(database.conninfo());
  const Site first = ensureSite(connection, "delft", 7415, {kOriginX, kOriginY, 0.0});
  const Site again = ensureSite(connection, "delft", 7415, {kOriginX, kOriginY, 0.0});
  EXPECT_EQ(first.id, again.id);
  EXPECT_THROW(ensureSite(connection, "delft", 28992, {kOriginX, kOriginY, 0.0}), DatabaseError);
  EXPECT_FALSE(findSite(connection, "nowhere").has_value());
}

TEST(ModelLineQuery, ReturnsExactlyTheLinesWithinTheRadiusInSiteCoordinates) {
  test::TestDatabase database("line_query");
  test::insertCubeBuilding(database.conninfo(), kOriginX, kOriginY, 0.0, 0.0);
  test::insertCubeBuilding(database.conninfo(), kOriginX, kOriginY, 500.0, 0.0);
  Connection connection(database.conninfo());
  const Site site = *findSite(connection, "test");
  ModelLineQuery query(connection, site);

  const std::vector<ModelLine> near_first = query.linesWithin({5.0, -20.0, 1.5}, 100.0);
  ASSERT_EQ(near_first.size(), 12u);
  for (const ModelLine& line : near_first) {
    EXPECT_LE(line.start_world.x(), 10.0);
    EXPECT_GE(line.start_world.x(), 0.0);
    EXPECT_NE(line.kind, LineKind::kOther);
  }
  EXPECT_EQ(query.linesWithin({505.0, 5.0, 5.0}, 1.0).size(), 0u);
  // Every edge of a 10 m cube is 5 sqrt(2) = 7.071 m from its centre.
  EXPECT_EQ(query.linesWithin({5.0, 5.0, 5.0}, 7.08).size(), 12u);
  EXPECT_EQ(query.linesWithin({5.0, 5.0, 5.0}, 7.06).size(), 0u);
  EXPECT_EQ(query.linesWithin({250.0, 0.0, 0.0}, 1000.0).size(), 24u);
  // Another query object on the same connection shares the prepared statement.
  ModelLineQuery second(connection, site);
  EXPECT_EQ(second.linesWithin({5.0, 5.0, 5.0}, 7.08).size(), 12u);
}

}  // namespace
}  // namespace lineloc::db
