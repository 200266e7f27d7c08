// The line packs and the queries over them on a real PostGIS server holding a
// synthetic city loaded by lineloc-load's pipeline: the packs the loader
// writes are byte for byte what SQL derives from the line table, the trigger
// keeps them in step with direct changes, and the view-frustum query returns
// exactly the lines a brute-force projection of every stored line sees.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>

#include "common/camera/camera_calibration.h"
#include "db/line_pack.h"
#include "db/loader/loader.h"
#include "db/model_line_query.h"
#include "db/site.h"
#include "tests/support/test_database.h"

namespace lineloc::db {
namespace {

const citymodel::SyntheticCityOptions kCity{.building_count = 300};

Site loadCity(Connection& connection) {
  LoadOptions options;
  options.site = "synthetic";
  storeModel(connection, options, {"city", "1", ""}, prepareSynthetic(kCity, options), nullptr);
  return *findSite(connection, options.site);
}

int count(Connection& connection, const std::string& sql) {
  return std::stoi(connection.exec(sql).text(0, 0));
}

// Packs that differ from what line_pack_of_building derives, or are missing.
int stalePacks(Connection& connection) {
  return count(connection,
               "SELECT count(*) FROM line_pack_of_building v FULL JOIN building_line_pack p "
               "USING (building_id) WHERE p.lines IS DISTINCT FROM v.lines OR "
               "NOT (p.bounds ~= v.bounds) OR p.site_id IS DISTINCT FROM v.site_id");
}

// Every stored line of the site, read row by row from table line as text.
std::map<int64_t, ModelLine> storedLines(Connection& connection, const Site& site) {
  const Result result = connection.execParams(
      "SELECT id, building_id, kind, coalesce(face_a, -1), coalesce(face_b, -1), "
      "ST_X(ST_StartPoint(geom)), ST_Y(ST_StartPoint(geom)), ST_Z(ST_StartPoint(geom)), "
      "ST_X(ST_EndPoint(geom)), ST_Y(ST_EndPoint(geom)), ST_Z(ST_EndPoint(geom)), "
      "coalesce(normal_a_x, 0), coalesce(normal_a_y, 0), coalesce(normal_a_z, 0), "
      "coalesce(normal_b_x, 0), coalesce(normal_b_y, 0), coalesce(normal_b_z, 0) "
      "FROM line WHERE site_id = $1",
      {std::to_string(site.id)});
  std::map<int64_t, ModelLine> lines;
  for (int row = 0; row < result.rows(); ++row) {
    const auto integer = [&](int column) { return std::stoll(result.text(row, column)); };
    const auto vector = [&](int column) {
      return Eigen::Vector3d(std::stod(result.text(row, column)),
                             std::stod(result.text(row, column + 1)),
                             std::stod(result.text(row, column + 2)));
    };
    ModelLine line;
    line.id = integer(0);
    line.building_id = integer(1);
    line.kind = static_cast<LineKind>(integer(2));
    line.face_a = static_cast<int>(integer(3));
    line.face_b = static_cast<int>(integer(4));
    line.start_world = vector(5) - site.origin;
    line.end_world = vector(8) - site.origin;
    line.normal_a = vector(11);
    line.normal_b = vector(14);
    lines.emplace(line.id, line);
  }
  return lines;
}

std::vector<ModelLine> unpackAll(Connection& connection, const Site& site) {
  connection.prepare("all_packs", "SELECT building_id, lines FROM building_line_pack");
  const Result packs = connection.execPrepared("all_packs", {}, true);
  std::vector<ModelLine> lines;
  for (int row = 0; row < packs.rows(); ++row) {
    decodeLinePack({packs.bytes(row, 1), static_cast<size_t>(packs.length(row, 1))},
                   packs.binaryInt8(row, 0), site.origin, lines);
  }
  return lines;
}

void expectSameLine(const ModelLine& a, const ModelLine& b) {
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.building_id, b.building_id);
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.start_world, b.start_world);
  EXPECT_EQ(a.end_world, b.end_world);
  EXPECT_EQ(a.face_a, b.face_a);
  EXPECT_EQ(a.face_b, b.face_b);
  EXPECT_EQ(a.normal_a, b.normal_a);
  EXPECT_EQ(a.normal_b, b.normal_b);
}

TEST(LinePacks, LoaderPacksAreWhatSqlDerivesAndDecodeToTheLineRows) {
  test::TestDatabase database("line_packs");
  Connection connection(database.conninfo());
  const Site site = loadCity(connection);
  EXPECT_EQ(count(connection, "SELECT count(*) FROM building_line_pack"), kCity.building_count);
  EXPECT_EQ(stalePacks(connection), 0);

  const std::map<int64_t, ModelLine> stored = storedLines(connection, site);
  const std::vector<ModelLine> unpacked = unpackAll(connection, site);
  ASSERT_EQ(unpacked.size(), stored.size());
  for (const ModelLine& line : unpacked) {
    const auto row = stored.find(line.id);
    ASSERT_NE(row, stored.end()) << "line " << line.id;
    expectSameLine(line, row->second);
  }
}

TEST(LinePacks, TheTriggerKeepsPacksInStepWithDirectChangesOfLines) {
  constexpr double kAway_m = 5000.0;
  test::TestDatabase database("line_pack_trigger");
  Connection connection(database.conninfo());
  const Site site = loadCity(connection);
  const std::string building = connection.exec("SELECT min(building_id) FROM line").text(0, 0);
  const auto lines_of = [&] {
    return count(connection,
                 "SELECT length(lines) / 114 FROM building_line_pack WHERE "
                 "building_id = " +
                     building);
  };
  const int before = lines_of();

  connection.exec(
      "UPDATE line SET geom = ST_Translate(geom, 0, 0, 1) WHERE id = (SELECT min(id) "
      "FROM line WHERE building_id = " +
      building + ")");
  EXPECT_EQ(stalePacks(connection), 0);
  connection.exec("DELETE FROM line WHERE id = (SELECT max(id) FROM line WHERE building_id = " +
                  building + ")");
  EXPECT_EQ(stalePacks(connection), 0);
  EXPECT_EQ(lines_of(), before - 1);
  connection.exec(
      fmt::format("INSERT INTO line (site_id, building_id, kind, geom) VALUES ({}, {}, 0, "
                  "ST_SetSRID(ST_MakeLine(ST_MakePoint({}, {}, 0), ST_MakePoint({}, {}, 3)), {}))",
                  site.id, building, site.origin.x() - kAway_m, site.origin.y(),
                  site.origin.x() - kAway_m, site.origin.y(), site.srid));
  EXPECT_EQ(stalePacks(connection), 0);
  EXPECT_EQ(lines_of(), before);
  // The added line, far west of the city, is found by the query through its pack.
  ModelLineQuery query(connection, site);
  const std::vector<ModelLine> added = query.linesWithin({-kAway_m, 0.0, 1.0}, 0.5);
  ASSERT_EQ(added.size(), 1u);
  EXPECT_EQ(added[0].end_world, Eigen::Vector3d(-kAway_m, 0.0, 3.0));

  connection.exec("DELETE FROM building WHERE id = " + building);
  EXPECT_EQ(
      count(connection, "SELECT count(*) FROM building_line_pack WHERE building_id = " + building),
      0);
  EXPECT_EQ(stalePacks(connection), 0);
  connection.exec("TRUNCATE line");
  EXPECT_EQ(count(connection, "SELECT count(*) FROM building_line_pack"), 0);
}

// A 640 x 480 camera with fx = fy = 500 (65 degrees across), seeing 0.5 to 120 m.
constexpr double kNear_m = 0.5;
constexpr double kFar_m = 120.0;

PinholeCamera streetCamera() {
  return {.fx = 500.0, .fy = 500.0, .cx = 320.0, .cy = 240.0, .width = 640, .height = 480};
}

// 1.6 m above a street point, looking level towards the site origin (the
// middle of the city) turned by `turn_rad`: camera z forward, x right, y down.
Eigen::Isometry3d streetPose(const Site& site, uint32_t draw, double turn_rad) {
  const Eigen::Vector2d street = citymodel::randomStreetPoint(kCity, draw);
  const Eigen::Vector3d position(street.x() - site.origin.x(), street.y() - site.origin.y(), 1.6);
  const double yaw = std::atan2(-position.y(), -position.x()) + turn_rad;
  const Eigen::Vector3d forward(std::cos(yaw), std::sin(yaw), 0.0);
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ());
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
  T_world_camera.linear() << right, forward.cross(right), forward;
  T_world_camera.translation() = position;
  return T_world_camera;
}

// Brute force: some of `samples` evenly spaced points of the line project into
// the image (widened by `margin_px`) at a depth within [near, far] (widened by
// `margin_m`).
bool seenBySampling(const Eigen::Isometry3d& T_camera_world, const PinholeCamera& camera,
                    const ModelLine& line, int samples, double margin_px, double margin_m) {
  for (int i = 0; i < samples; ++i) {
    const double s = static_cast<double>(i) / (samples - 1);
    const Eigen::Vector3d p =
        T_camera_world * (line.start_world + s * (line.end_world - line.start_world));
    if (p.z() < kNear_m - margin_m || p.z() > kFar_m + margin_m) {
      continue;
    }
    const Eigen::Vector2d uv = camera.project(p);
    if (uv.x() >= -margin_px && uv.x() <= camera.width + margin_px && uv.y() >= -margin_px &&
        uv.y() <= camera.height + margin_px) {
      return true;
    }
  }
  return false;
}

TEST(ModelLineQuery, FrustumLinesAreThoseABruteForceProjectionOfEveryLineSees) {
  test::TestDatabase database("frustum_query");
  Connection connection(database.conninfo());
  const Site site = loadCity(connection);
  const std::map<int64_t, ModelLine> stored = storedLines(connection, site);
  const PinholeCamera camera = streetCamera();
  ModelLineQuery query(connection, site);
  for (uint32_t draw = 0; draw < 4; ++draw) {
    const Eigen::Isometry3d T_world_camera = streetPose(site, draw, 0.4 * draw - 0.6);
    const Eigen::Isometry3d T_camera_world = T_world_camera.inverse();
    const std::vector<ModelLine> found =
        query.linesInFrustum(T_world_camera, camera, kNear_m, kFar_m);
    std::set<int64_t> found_ids;
    for (const ModelLine& line : found) {
      found_ids.insert(line.id);
      expectSameLine(line, stored.at(line.id));
    }
    int seen = 0;
    for (const auto& [id, line] : stored) {
      if (seenBySampling(T_camera_world, camera, line, 101, 0.0, 0.0)) {
        ++seen;
        EXPECT_TRUE(found_ids.count(id)) << "line " << id << " is seen but was not returned";
      }
    }
    EXPECT_GT(seen, 20) << "pose " << draw << " sees too little to test anything";
    // Returned lines the coarse sampling missed touch the frustum between two
    // samples: resampled every 1 mm, some sample lies within 0.5 mm of the
    // frustum, i.e. within 0.5 mm in depth and, at depth >= 0.5 m, within
    // fx (1 + tan(half field of view)) 0.5 mm / 0.5 m = 500 * 1.64 * 1e-3 =
    // 0.82 px of the image border.
    for (const ModelLine& line : found) {
      const double length_m = (line.end_world - line.start_world).norm();
      const int dense = std::max(2, static_cast<int>(std::ceil(length_m / 1e-3)) + 1);
      EXPECT_TRUE(seenBySampling(T_camera_world, camera, line, dense, 1.0, 1e-3))
          << "line " << line.id << " was returned but lies outside the frustum";
    }
  }
}

}  // namespace
}  // namespace lineloc::db
