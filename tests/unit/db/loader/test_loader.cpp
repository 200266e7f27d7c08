// lineloc-load's pipeline on a real PostGIS server: loads are idempotent and
// transactional (a failure or a killed loader leaves the previous state), and
// the backbone's read-only role can read but not write (the real files of
// ../shared/data load in test_loader_shared_models.cpp).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "db/enrichment_store.h"
#include "db/loader/line_export.h"
#include "db/loader/loader.h"
#include "db/model_line_query.h"
#include "db/site.h"
#include "tests/support/test_database.h"

namespace lineloc::db {
namespace {

int count(Connection& connection, const std::string& sql) {
  return std::stoi(connection.exec(sql).text(0, 0));
}

TEST(Loader, ReloadingTheSameFileChangesNothing) {
  test::TestDatabase database("loader_reload");
  Connection connection(database.conninfo(test::DatabaseRole::kWriter));
  const std::string path =
      (std::filesystem::path(LINELOC_SOURCE_DIR) / "data" / "citymodels" / "delft.json").string();
  const std::string snapshot_sql =
      "SELECT string_agg(b.id || '/' || b.loaded_at || '/' || "
      "(SELECT count(*) FROM line l WHERE l.building_id = b.id), ',' ORDER BY b.id) FROM building "
      "b";
  EXPECT_FALSE(loadFile(path, {}, &connection, nullptr).unchanged);
  const std::string before = connection.exec(snapshot_sql).text(0, 0);
  const int lines = count(connection, "SELECT count(*) FROM line");
  EXPECT_TRUE(loadFile(path, {}, &connection, nullptr).unchanged);
  EXPECT_EQ(connection.exec(snapshot_sql).text(0, 0), before);
  EXPECT_EQ(count(connection, "SELECT count(*) FROM line"), lines);
}

std::string writeTemporary(const std::string& name, const std::string& text) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / fmt::format("{}-{}", getpid(), name);
  std::ofstream(path) << text;
  return path.string();
}

// A 10 m cube per id, side by side along x.
std::string cubes(const std::vector<std::string>& ids, const std::string& broken_id = "") {
  std::string objects, vertices;
  for (size_t i = 0; i < ids.size(); ++i) {
    const int base = static_cast<int>(8 * i);
    const auto v = [&](int k) { return base + k + (ids[i] == broken_id && k == 1 ? 999 : 0); };
    objects += fmt::format(
        R"({}"{}":{{"type":"Building","geometry":[{{"type":"Solid","lod":"1","boundaries":[[[[{},{},{},{}]],[[{},{},{},{}]],[[{},{},{},{}]],[[{},{},{},{}]],[[{},{},{},{}]],[[{},{},{},{}]]]]}}]}})",
        i == 0 ? "" : ",", ids[i], v(0), v(3), v(2), v(1), v(4), v(5), v(6), v(7), v(0), v(1), v(5),
        v(4), v(1), v(2), v(6), v(5), v(2), v(3), v(7), v(6), v(3), v(0), v(4), v(7));
    const int x = 20 * static_cast<int>(i);
    for (const auto& [dx, dy, z] : std::vector<std::tuple<int, int, int>>{{0, 0, 0},
                                                                          {10, 0, 0},
                                                                          {10, 10, 0},
                                                                          {0, 10, 0},
                                                                          {0, 0, 10},
                                                                          {10, 0, 10},
                                                                          {10, 10, 10},
                                                                          {0, 10, 10}}) {
      vertices += fmt::format("{}[{},{},{}]", vertices.empty() ? "" : ",", x + dx, dy, z);
    }
  }
  return fmt::format(
      R"({{"type":"CityJSON","version":"2.0","transform":{{"scale":[1,1,1],"translate":[85000,447000,0]}},"metadata":{{"referenceSystem":"https://www.opengis.net/def/crs/EPSG/0/7415"}},"CityObjects":{{{}}},"vertices":[{}]}})",
      objects, vertices);
}

TEST(Loader, AFailedLoadLeavesThePreviousVersionAndSkipInvalidCounts) {
  test::TestDatabase database("loader_failure");
  Connection connection(database.conninfo(test::DatabaseRole::kWriter));
  const std::string path = writeTemporary("block.json", cubes({"a", "b"}));
  loadFile(path, {}, &connection, nullptr);
  EXPECT_EQ(count(connection, "SELECT count(*) FROM line"), 24);

  std::ofstream(path) << cubes({"a", "b", "c"}, "c");
  EXPECT_THROW(loadFile(path, {}, &connection, nullptr), citymodel::ModelError);
  EXPECT_EQ(count(connection, "SELECT count(*) FROM building"), 2);
  EXPECT_EQ(count(connection, "SELECT count(*) FROM line"), 24);

  LoadOptions skip;
  skip.read.invalid_objects = citymodel::InvalidObjectPolicy::kSkip;
  const LoadReport report = loadFile(path, skip, &connection, nullptr);
  EXPECT_EQ(report.skipped.count_by_reason.at("vertex index out of range"), 1);
  EXPECT_EQ(count(connection, "SELECT count(*) FROM building"), 2);

  std::ofstream(path) << cubes({"a"});
  LoadOptions dry_run;
  dry_run.dry_run = true;
  EXPECT_EQ(loadFile(path, dry_run, &connection, nullptr).lines, 12);
  EXPECT_EQ(count(connection, "SELECT count(*) FROM line"), 24) << "a dry run writes nothing";
  loadFile(path, {}, &connection, nullptr);
  EXPECT_EQ(count(connection, "SELECT count(*) FROM line"), 12) << "a new version replaces";
  std::filesystem::remove(path);
}

TEST(Loader, AKilledLoaderLeavesThePreviousState) {
  test::TestDatabase database("loader_killed");
  LoadOptions options;
  options.site = "synthetic";
  const SourceRecord record{"city", "v1", ""};
  {
    Connection connection(database.conninfo(test::DatabaseRole::kWriter));
    storeModel(connection, options, record, prepareSynthetic({.building_count = 50}, options),
               nullptr);
  }
  const PreparedModel bigger = prepareSynthetic({.building_count = 3000, .seed = 2}, options);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // The child replaces the city and dies by SIGKILL halfway through writing lines.
    Connection connection(database.conninfo(test::DatabaseRole::kWriter));
    storeModel(connection, options, {"city", "v2", ""}, bigger, [](size_t done, size_t) {
      if (done == 1500)
        raise(SIGKILL);
    });
    _exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  Connection connection(database.conninfo(test::DatabaseRole::kWriter));
  EXPECT_EQ(count(connection, "SELECT count(*) FROM building"), 50);
  EXPECT_EQ(connection.exec("SELECT hash FROM source_file").text(0, 0), "v1");
}

// Each statement a role may not run, refused with the server's message.
void expectRefused(Connection& connection, const std::vector<std::string>& statements) {
  for (const std::string& sql : statements) {
    EXPECT_THROW(connection.exec(sql), DatabaseError) << sql;
  }
}

TEST(Loader, ReaderRoleSelectsButCannotWrite) {
  test::TestDatabase database("loader_reader_role");
  test::insertCubeBuilding(database.conninfo(), 85000, 447000, 0, 0);
  Connection reader(database.conninfo(test::DatabaseRole::kReader));
  EXPECT_EQ(count(reader, "SELECT count(*) FROM line"), 12);
  // The backbone's query reads the line packs.
  ModelLineQuery query(reader, *findSite(reader, "test"));
  EXPECT_EQ(query.linesWithin({5.0, 5.0, 5.0}, 10.0).size(), 12u);
  expectRefused(reader,
                {"DELETE FROM line", "DELETE FROM building_line_pack",
                 "INSERT INTO site (name, srid, origin_x, origin_y) VALUES ('x', 1, 0, 0)",
                 "UPDATE site SET name = 'x'", "UPDATE schema_migrations SET version = 0",
                 "SELECT nextval('line_id_seq')", "COPY site FROM STDIN", "TRUNCATE line",
                 "CREATE TABLE x (a int)", "CREATE TABLE public.x (a int)", "CREATE SCHEMA x",
                 "ALTER TABLE line ADD COLUMN x int", "DROP TABLE line"});
  EXPECT_EQ(count(reader, "SELECT count(*) FROM line"), 12);
}

TEST(Loader, WriterRoleLoadsRowsButCannotChangeTheSchema) {
  test::TestDatabase database("loader_writer_role");
  Connection writer(database.conninfo(test::DatabaseRole::kWriter));
  const std::string path = writeTemporary("writer.json", cubes({"a", "b"}));
  loadFile(path, {}, &writer, nullptr);
  std::filesystem::remove(path);
  EXPECT_EQ(count(writer, "SELECT count(*) FROM line"), 24);
  writer.exec("UPDATE site SET origin_z = 1");
  writer.exec("DELETE FROM source_file");
  expectRefused(
      writer,
      {"CREATE TABLE x (a int)", "CREATE TABLE public.x (a int)", "CREATE SCHEMA x",
       "CREATE INDEX x ON line (kind)", "ALTER TABLE line ADD COLUMN x int",
       "ALTER TABLE line DISABLE TRIGGER line_packs_after_insert", "DROP TABLE terrain_triangle",
       "TRUNCATE line", "CREATE FUNCTION x() RETURNS int LANGUAGE sql AS 'SELECT 1'",
       "COPY site TO PROGRAM 'true'", "COPY site FROM PROGRAM 'true'",
       "INSERT INTO schema_migrations (version, name) VALUES (9999, 'x')",
       "DELETE FROM schema_migrations", "SET ROLE lineloc_owner"});
  EXPECT_EQ(count(writer, "SELECT count(*) FROM line"), 24);
}

TEST(Loader, AModelThatNamesNoCrsIsRefusedUnlessALocalFrameIsAllowed) {
  // A 30 cm box in its own frame, no referenceSystem.
  const std::string box = R"({"type":"CityJSON","version":"2.0",
 "transform":{"scale":[0.001,0.001,0.001],"translate":[0,0,0]},
 "CityObjects":{"box":{"type":"Building","geometry":[{"type":"Solid","lod":"2","boundaries":
 [[[[0,3,2,1]],[[4,5,6,7]],[[0,1,5,4]],[[1,2,6,5]],[[2,3,7,6]],[[3,0,4,7]]]]}]}},
 "vertices":[[0,0,0],[300,0,0],[300,200,0],[0,200,0],[0,0,100],[300,0,100],[300,200,100],
 [0,200,100]]})";
  LoadOptions options;
  try {
    prepareModel(box, "box.city.json", InputFormat::kCityJson, options, std::nullopt);
    FAIL() << "a model without a CRS loaded into a site";
  } catch (const citymodel::ModelError& error) {
    EXPECT_EQ(error.reason(), "no CRS");
    EXPECT_NE(std::string(error.what()).find("box.city.json"), std::string::npos);
  }
  options.local_frame_allowed = true;
  const PreparedModel local =
      prepareModel(box, "box.city.json", InputFormat::kCityJson, options, std::nullopt);
  EXPECT_EQ(local.source_epsg, 0);
  ASSERT_EQ(local.model.buildings.size(), 1u);
  EXPECT_TRUE(local.model.buildings[0].faces[1].rings[0][2].isApprox(
      Eigen::Vector3d(0.3, 0.2, 0.1)));
  EXPECT_EQ(local.lines.at(0).size(), 12u);
  // Nor can a local frame be moved into a CRS.
  EXPECT_THROW(prepareModel(box, "box.city.json", InputFormat::kCityJson, options, 28992),
               citymodel::ModelError);
  // A CRS given for it is used as before.
  options.file_epsg = 28992;
  EXPECT_EQ(prepareModel(box, "box.city.json", InputFormat::kCityJson, options, std::nullopt)
                .source_epsg,
            28992);
}

TEST(Loader, LinesQueryAndExportOfASyntheticCity) {
  test::TestDatabase database("loader_query");
  Connection connection(database.conninfo(test::DatabaseRole::kWriter));
  LoadOptions options;
  options.site = "synthetic";
  const citymodel::SyntheticCityOptions city{.building_count = 400};
  const PreparedModel prepared = prepareSynthetic(city, options);
  storeModel(connection, options, {"city", "1", ""}, prepared, nullptr);
  const Site site = *findSite(connection, "synthetic");
  ModelLineQuery query(connection, site);
  for (uint32_t draw = 0; draw < 5; ++draw) {
    const Eigen::Vector2d street = citymodel::randomStreetPoint(city, draw);
    const Eigen::Vector3d centre(street.x() - site.origin.x(), street.y() - site.origin.y(), 1.5);
    const int plain =
        count(connection, fmt::format("SELECT count(*) FROM line WHERE ST_3DDWithin(geom, "
                                      "ST_SetSRID(ST_MakePoint({:.6f}, {:.6f}, 1.5), {}), 60)",
                                      street.x(), street.y(), site.srid));
    EXPECT_GT(plain, 0);
    EXPECT_EQ(static_cast<int>(query.linesWithin(centre, 60.0).size()), plain);
  }
  const std::string path = writeTemporary("lines.obj", "");
  size_t expected_lines = 0;
  for (const auto& lines : prepared.lines)
    expected_lines += lines.size();
  EXPECT_EQ(exportLines(connection, site, path), static_cast<int>(expected_lines));
  std::ifstream exported(path);
  size_t l_elements = 0;
  for (std::string line; std::getline(exported, line);)
    l_elements += line.starts_with("l ");
  EXPECT_EQ(l_elements, expected_lines);
  std::filesystem::remove(path);
}

TEST(LineExport, LearntLinesOfTheStatusAskedFollowTheModels) {
  test::TestDatabase database("line_export_learnt");
  Connection owner(database.conninfo());
  const Site site = ensureSite(owner, "learnt", 7415, {85000.0, 447000.0, 0.0});
  Connection enricher(database.conninfo(test::DatabaseRole::kEnricher));
  const auto sighting = [](double height_m, const std::string& robot) {
    EnrichmentSighting line;
    line.start_world = {10.0, 5.0, height_m};
    line.end_world = {10.0, 6.2, height_m};
    line.start_covariance = line.end_covariance = Eigen::Matrix3d::Identity() * 1e-4;
    line.plane_normal = -Eigen::Vector3d::UnitX();
    line.plane_offset = -10.0;
    line.robot = robot;
    line.views = 5;
    return line;
  };
  writeEnrichmentPass(enricher, site, "monday", {sighting(3.5, "r1"), sighting(6.4, "r1")});
  writeEnrichmentPass(enricher, site, "tuesday", {sighting(3.5, "r2")});
  const std::string path = writeTemporary("learnt.geojson", "");
  EXPECT_EQ(exportLines(owner, site, path), 0);
  EnrichmentFilter confirmed;
  confirmed.status = EnrichmentStatus::kConfirmed;
  EXPECT_EQ(exportLines(owner, site, path, confirmed), 1);
  const nlohmann::json document = nlohmann::json::parse(std::ifstream(path));
  const nlohmann::json& properties = document["features"][0]["properties"];
  EXPECT_EQ(properties["kind"], "learnt");
  EXPECT_EQ(properties["status"], "confirmed");
  EXPECT_EQ(properties["passes"], 2);
  EXPECT_NEAR(document["features"][0]["geometry"]["coordinates"][0][0].get<double>(), 85010.0,
              1e-9);
  EXPECT_EQ(exportLines(owner, site, path, EnrichmentFilter{}), 2);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace lineloc::db
