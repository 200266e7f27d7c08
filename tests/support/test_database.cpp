#include "tests/support/test_database.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <stdexcept>

#include "db/connection.h"
#include "db/migrations.h"
#include "db/site.h"

namespace lineloc::test {

namespace {

const char* roleName(DatabaseRole role) {
  switch (role) {
    case DatabaseRole::kOwner:
      return "lineloc_owner";
    case DatabaseRole::kWriter:
      return "lineloc_writer";
    case DatabaseRole::kReader:
      return "lineloc_reader";
    case DatabaseRole::kEnricher:
      return "lineloc_enricher";
  }
  throw std::invalid_argument("unknown database role");
}

}  // namespace

std::string clusterConninfo(const std::string& port, DatabaseRole role) {
  const std::string command = fmt::format("LINELOC_PG_PORT='{}' '{}/deploy/pg.sh' conninfo {}",
                                          port, LINELOC_SOURCE_DIR, roleName(role));
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    throw std::runtime_error("could not run " + command);
  }
  std::string conninfo;
  char buffer[256];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) {
    conninfo += buffer;
  }
  if (pclose(pipe) != 0 || conninfo.empty()) {
    throw std::runtime_error(command + " failed");
  }
  conninfo.erase(conninfo.find_last_not_of('\n') + 1);
  return conninfo;
}

namespace {

std::string testClusterPort() {
  const char* port = std::getenv("LINELOC_TEST_PG_PORT");
  if (port == nullptr) {
    throw std::runtime_error(
        "LINELOC_TEST_PG_PORT is not set: run this test through ctest (fixture 'postgis')");
  }
  return port;
}

void runPgScript(const std::string& port, const std::string& arguments) {
  const std::string command = fmt::format("LINELOC_PG_PORT='{}' '{}/deploy/pg.sh' {} >/dev/null",
                                          port, LINELOC_SOURCE_DIR, arguments);
  if (std::system(command.c_str()) != 0) {
    throw std::runtime_error(command + " failed");
  }
}

}  // namespace

std::string testClusterConninfo(const std::string& database, DatabaseRole role) {
  const std::string port = testClusterPort();
  // deploy/pg.sh runs once per role and process.
  static std::mutex mutex;
  static std::map<DatabaseRole, std::string> cluster_conninfo;
  const std::lock_guard lock(mutex);
  auto known = cluster_conninfo.find(role);
  if (known == cluster_conninfo.end()) {
    known = cluster_conninfo.emplace(role, clusterConninfo(port, role)).first;
  }
  // libpq takes the last value of a repeated keyword.
  return fmt::format("{} dbname={}", known->second, database);
}

TestReplica::TestReplica() : port_(std::to_string(std::stoi(testClusterPort()) + 1)) {
  runPgScript(port_, "destroy");
  runPgScript(port_, "replicate " + testClusterPort());
}

TestReplica::~TestReplica() {
  try {
    runPgScript(port_, "destroy");
  } catch (const std::exception&) {
    // Nothing more to clean.
  }
}

std::string TestReplica::conninfo(const std::string& database, DatabaseRole role) const {
  return fmt::format("{} dbname={}", clusterConninfo(port_, role), database);
}

void TestReplica::run(const std::string& command) const {
  runPgScript(port_, command);
}

TestDatabase::TestDatabase(const std::string& name)
    : admin_conninfo_(testClusterConninfo("postgres")),
      database_(fmt::format("test_{}_{}", name, getpid())) {
  db::Connection admin(admin_conninfo_);
  admin.exec(fmt::format("DROP DATABASE IF EXISTS {} WITH (FORCE)", database_));
  admin.exec(fmt::format("CREATE DATABASE {} TEMPLATE template1", database_));
  db::Connection connection(conninfo());
  db::applyMigrations(connection, db::embeddedMigrations());
}

std::string TestDatabase::conninfo(DatabaseRole role) const {
  return testClusterConninfo(database_, role);
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
