// A streaming replica of the private cluster (deploy/pg.sh replicate): it
// follows what is written to its primary, no role can write to it, and a
// backbone's map tiles read through a connection string naming the replica
// and then the primary keep coming when the replica stops.
#include <gtest/gtest.h>
#include <libpq-fe.h>

#include <chrono>
#include <string>
#include <thread>

#include "backbone/map/database_tile_fetcher.h"
#include "db/connection.h"
#include "tests/support/test_database.h"
#include "tests/support/wait_for.h"

namespace lineloc {
namespace {

using test::DatabaseRole;

// The database name in `conninfo` ("... dbname=NAME" last, as TestDatabase gives it).
std::string databaseOf(const std::string& conninfo) {
  return conninfo.substr(conninfo.rfind("dbname=") + 7);
}

bool inRecovery(db::Connection& connection) {
  return std::string(PQgetvalue(connection.exec("SELECT pg_is_in_recovery()").get(), 0, 0)) == "t";
}

TEST(PgReplica, FollowsItsPrimaryReadOnlyAndReadersFailOverToThePrimary) {
  test::TestDatabase database("replica");
  test::insertCubeBuilding(database.conninfo(DatabaseRole::kWriter), 85000, 447000, 0, 0);
  const test::TestReplica replica;
  const std::string name = databaseOf(database.conninfo());

  // The database and its building reach the replica.
  ASSERT_TRUE(test::waitFor(
      [&] {
        try {
          db::Connection reader(replica.conninfo(name, DatabaseRole::kReader));
          return std::string(PQgetvalue(reader.exec("SELECT count(*) FROM lineloc.line").get(), 0,
                                        0)) == "12";
        } catch (const db::DatabaseError&) {
          return false;
        }
      },
      std::chrono::seconds(30)));
  db::Connection writer(replica.conninfo(name, DatabaseRole::kWriter));
  EXPECT_TRUE(inRecovery(writer));
  try {
    writer.exec("DELETE FROM lineloc.line");
    FAIL() << "wrote to the replica";
  } catch (const db::DatabaseError& error) {
    EXPECT_NE(std::string(error.what()).find("read-only transaction"), std::string::npos)
        << error.what();
  }

  // A reader naming the replica first reads from it, and from the primary
  // once the replica is stopped, with no failed fetch.
  const std::string primary = database.conninfo(DatabaseRole::kReader);
  const std::string both = "host=127.0.0.1,127.0.0.1 port=" + replica.port() + "," +
                           primary.substr(primary.find("port=") + 5, 5) +
                           " target_session_attrs=prefer-standby " +
                           replica.conninfo(name, DatabaseRole::kReader)
                               .substr(replica.conninfo(name, DatabaseRole::kReader).find("user="));
  {
    db::Connection through_both(both);
    EXPECT_TRUE(inRecovery(through_both));
  }
  TileFetcher fetch = makeDatabaseTileFetcher(both, "test");
  const Eigen::AlignedBox2d around_cube(Eigen::Vector2d(-5, -5), Eigen::Vector2d(15, 15));
  EXPECT_EQ(fetch(around_cube).lines.size(), 12u);
  replica.run("stop");
  EXPECT_EQ(fetch(around_cube).lines.size(), 12u);
  db::Connection after(both);
  EXPECT_FALSE(inRecovery(after));
}

}  // namespace
}  // namespace lineloc
