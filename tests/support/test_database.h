// A fresh, migrated PostGIS database for one test, on the private test cluster
// that the CTest fixture "postgis" starts with deploy/pg.sh (port from
// LINELOC_TEST_PG_PORT). Dropped again when the object goes away.
#pragma once

#include <string>

namespace lineloc::test {

class TestDatabase {
 public:
  // `name` distinguishes databases of tests running in parallel.
  explicit TestDatabase(const std::string& name);
  ~TestDatabase();
  TestDatabase(const TestDatabase&) = delete;
  TestDatabase& operator=(const TestDatabase&) = delete;

  const std::string& conninfo() const { return conninfo_; }

 private:
  std::string admin_conninfo_;
  std::string database_;
  std::string conninfo_;
};

// libpq connection string of the test cluster's database `database`.
std::string testClusterConninfo(const std::string& database);

// Inserts site 'test' (EPSG:7415, origin `origin`) and a 10 m cube at the site
// origin offset by `corner_world` (12 lines, 6 faces); returns the site id.
int insertCubeBuilding(const std::string& conninfo, double origin_x, double origin_y,
                       double corner_x, double corner_y);

}  // namespace lineloc::test
