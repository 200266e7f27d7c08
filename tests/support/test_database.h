// A fresh, migrated PostGIS database for one test, on the private test cluster
// that the CTest fixture "postgis" starts with deploy/pg.sh (port from
// LINELOC_TEST_PG_PORT). Dropped again when the object goes away. Connection
// strings are the ones deploy/pg.sh prints, with the passwords it keeps.
#pragma once

#include <string>

namespace lineloc::test {

// The roles deploy/pg.sh makes for lineloc's programs (docs/production.md):
// the owner runs migrations (and, on the test cluster, creates databases),
// the writer loads rows (lineloc-load), the reader reads (lineloc-backbone).
enum class DatabaseRole { kOwner, kWriter, kReader, kEnricher };

// `deploy/pg.sh conninfo ROLE` for the cluster on `port`: the libpq
// connection string of its database lineloc, password file included.
std::string clusterConninfo(const std::string& port, DatabaseRole role);

// libpq connection string of the test cluster's database `database` as `role`.
std::string testClusterConninfo(const std::string& database,
                                DatabaseRole role = DatabaseRole::kOwner);

class TestDatabase {
 public:
  // `name` distinguishes databases of tests running in parallel.
  explicit TestDatabase(const std::string& name);
  ~TestDatabase();
  TestDatabase(const TestDatabase&) = delete;
  TestDatabase& operator=(const TestDatabase&) = delete;

  // The owner's by default: it migrated the database and may change anything.
  std::string conninfo(DatabaseRole role = DatabaseRole::kOwner) const;

 private:
  std::string admin_conninfo_;
  std::string database_;
};

// A streaming replica of the test cluster (deploy/pg.sh replicate) on the
// port after the cluster's, for one test: made anew, destroyed afterwards.
// One test at a time may hold it.
class TestReplica {
 public:
  TestReplica();
  ~TestReplica();
  TestReplica(const TestReplica&) = delete;
  TestReplica& operator=(const TestReplica&) = delete;

  const std::string& port() const { return port_; }
  // libpq connection string of the replica's database `database` as `role`.
  std::string conninfo(const std::string& database, DatabaseRole role) const;
  // deploy/pg.sh `command` ("stop", "start") on the replica.
  void run(const std::string& command) const;

 private:
  std::string port_;
};

// Inserts site 'test' (EPSG:7415, origin `origin`) and a 10 m cube at the site
// origin offset by `corner_world` (12 lines, 6 faces); returns the site id.
int insertCubeBuilding(const std::string& conninfo, double origin_x, double origin_y,
                       double corner_x, double corner_y);

}  // namespace lineloc::test
