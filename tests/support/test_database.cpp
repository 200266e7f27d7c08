#include "tests/support/test_database.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <stdexcept>

#include "db/connection.h"
#include "db/migrations.h"
#include "db/site.h"

namespace lineloc::test {

std::string testClusterConninfo(const std::string& database) {
  const char* port = std::getenv("LINELOC_TEST_PG_PORT");
  if (port == nullptr) {
    throw std::runtime_error(
        "LINELOC_TEST_PG_PORT is not set: run this test through ctest (fixture 'postgis')");
  }
  return fmt::format("host=127.0.0.1 port={} user=lineloc dbname={}", port, database);
}

TestDatabase::TestDatabase(const std::string& name)
    : admin_conninfo_(testClusterConninfo("postgres")),
      database_(fmt::format("test_{}_{}", name, getpid())),
      conninfo_(testClusterConninfo(database_)) {
  db::Connection admin(admin_conninfo_);
  admin.exec(fmt::format("DROP DATABASE IF EXISTS {} WITH (FORCE)", database_));
  admin.exec(fmt::format("CREATE DATABASE {} TEMPLATE template1", database_));
  db::Connection connection(conninfo_);
  db::applyMigrations(connection, db::embeddedMigrations());
}

TestDatabase::~TestDatabase() {
  try {
    db::Connection admin(admin_conninfo_);
    admin.exec(fmt::format("DROP DATABASE IF EXISTS {} WITH (FORCE)", database_));
  } catch (const std::exception&) {
    // The cluster may already be gone at the end of a run; nothing to clean then.
  }
}

int insertCubeBuilding(const std::string& conninfo, double origin_x, double origin_y,
                       double corner_x, double corner_y) {
  db::Connection connection(conninfo);
  const db::Site site = db::ensureSite(connection, "test", 7415, {origin_x, origin_y, 0.0});
  const std::string building_id =
      connection
          .execParams(
              "INSERT INTO building (site_id, source, source_id) VALUES ($1, 'test', "
              "$2) RETURNING id",
              {std::to_string(site.id), fmt::format("cube-{}-{}", corner_x, corner_y)})
          .text(0, 0);
  const double x0 = origin_x + corner_x;
  const double y0 = origin_y + corner_y;
  // Bottom square, top square, four verticals: kind 4 ground, 2 eave, 1 vertical.
  const double corners[4][2] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    const auto segment = [&](double za, double zb, double xa, double ya, double xb, double yb,
                             int kind) {
      connection.execParams(
          "INSERT INTO line (site_id, building_id, kind, geom) VALUES ($1, $2, $3, "
          "ST_SetSRID(ST_MakeLine(ST_MakePoint($4::float8, $5::float8, $6::float8), "
          "ST_MakePoint($7::float8, $8::float8, $9::float8)), 7415))",
          {std::to_string(site.id), building_id, std::to_string(kind), fmt::format("{}", xa),
           fmt::format("{}", ya), fmt::format("{}", za), fmt::format("{}", xb),
           fmt::format("{}", yb), fmt::format("{}", zb)});
    };
    const double xa = x0 + corners[i][0], ya = y0 + corners[i][1];
    const double xb = x0 + corners[j][0], yb = y0 + corners[j][1];
    segment(0, 0, xa, ya, xb, yb, 4);
    segment(10, 10, xa, ya, xb, yb, 2);
    segment(0, 10, xa, ya, xa, ya, 1);
  }
  return site.id;
}

}  // namespace lineloc::test
