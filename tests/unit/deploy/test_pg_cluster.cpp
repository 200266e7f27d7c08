// The private cluster deploy/pg.sh runs, as the test fixture started it: it
// trusts no one (pg_hba.conf), every role needs its password, and no role
// lineloc's programs log in as is a superuser or may run programs on the
// server.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <libpq-fe.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "db/connection.h"
#include "tests/support/test_database.h"

namespace lineloc {
namespace {

using test::DatabaseRole;

constexpr DatabaseRole kRoles[] = {DatabaseRole::kOwner, DatabaseRole::kWriter,
                                   DatabaseRole::kReader};

// The value of `keyword` in the libpq connection string `conninfo`.
std::string conninfoValue(const std::string& conninfo, const std::string& keyword) {
  char* error = nullptr;
  std::unique_ptr<PQconninfoOption, decltype(&PQconninfoFree)> options(
      PQconninfoParse(conninfo.c_str(), &error), &PQconninfoFree);
  PQfreemem(error);
  for (PQconninfoOption* option = options.get(); option != nullptr && option->keyword != nullptr;
       ++option) {
    if (keyword == option->keyword && option->val != nullptr) {
      return option->val;
    }
  }
  return "";
}

// The cluster's data directory, which holds the password file pg.sh names.
std::filesystem::path dataDirectory() {
  return std::filesystem::path(conninfoValue(test::testClusterConninfo("postgres"), "passfile"))
      .parent_path();
}

// Why a connection as `conninfo` failed; empty when it succeeded.
std::string connectionError(const std::string& conninfo) {
  std::unique_ptr<PGconn, decltype(&PQfinish)> connection(PQconnectdb(conninfo.c_str()), &PQfinish);
  if (PQstatus(connection.get()) == CONNECTION_OK) {
    return "";
  }
  return PQerrorMessage(connection.get());
}

TEST(PgCluster, HbaTrustsNoOneAndAsksEveryoneForAPassword) {
  std::ifstream hba(dataDirectory() / "pg_hba.conf");
  ASSERT_TRUE(hba) << "no pg_hba.conf in " << dataDirectory();
  int rules = 0;
  for (std::string line; std::getline(hba, line);) {
    std::istringstream words(line.substr(0, line.find('#')));
    std::vector<std::string> fields;
    for (std::string word; words >> word;) {
      fields.push_back(word);
    }
    if (fields.empty()) {
      continue;
    }
    ++rules;
    EXPECT_TRUE(fields.back() == "scram-sha-256" || fields.back() == "reject") << line;
    EXPECT_EQ(line.find("trust"), std::string::npos) << line;
  }
  EXPECT_GT(rules, 0);
}

TEST(PgCluster, RefusesEveryRoleWithoutItsPassword) {
  const std::string port = std::getenv("LINELOC_TEST_PG_PORT");
  for (const std::string role :
       {"lineloc", "lineloc_owner", "lineloc_writer", "lineloc_reader", "postgres"}) {
    for (const std::string& host : {std::string("127.0.0.1"), dataDirectory().string()}) {
      const std::string conninfo = fmt::format(
          "host='{}' port={} user={} dbname=postgres passfile=/dev/null "
          "connect_timeout=10",
          host, port, role);
      EXPECT_NE(connectionError(conninfo).find("password"), std::string::npos)
          << role << " at " << host << ": " << connectionError(conninfo);
      EXPECT_NE(connectionError(conninfo + " password=wrong").find("password"), std::string::npos)
          << role << " at " << host;
    }
  }
  for (const DatabaseRole role : kRoles) {
    EXPECT_EQ(connectionError(test::testClusterConninfo("postgres", role)), "");
  }
}

// It streams to a replica (test_pg_replica.cpp) and logs in nowhere else.
TEST(PgCluster, TheReplicationRoleLogsInToNoDatabase) {
  const std::string error =
      connectionError(test::testClusterConninfo("postgres") + " user=lineloc_replication");
  EXPECT_NE(error.find("pg_hba.conf rejects connection"), std::string::npos) << error;
}

TEST(PgCluster, NoRoleOfTheProgramsIsASuperuserOrRunsServerPrograms) {
  db::Connection owner(test::testClusterConninfo("postgres"));
  const db::Result superusers =
      owner.exec("SELECT string_agg(rolname, ',' ORDER BY rolname) FROM pg_roles WHERE rolsuper");
  EXPECT_EQ(superusers.text(0, 0), "lineloc") << "the setup superuser alone";
  const db::Result powerful = owner.exec(
      "SELECT count(*) FROM pg_roles WHERE rolname LIKE 'lineloc\\_%' AND (rolcreaterole OR "
      "(rolreplication AND rolname <> 'lineloc_replication') OR rolbypassrls OR "
      "pg_has_role(oid, 'pg_execute_server_program', 'USAGE') OR "
      "pg_has_role(oid, 'pg_write_server_files', 'USAGE') OR pg_has_role(oid, "
      "'pg_read_server_files', 'USAGE'))");
  EXPECT_EQ(powerful.text(0, 0), "0") << "replication is the replication role's alone";
  for (const DatabaseRole role : kRoles) {
    db::Connection connection(test::testClusterConninfo("postgres", role));
    EXPECT_THROW(connection.exec("COPY (SELECT 1) TO PROGRAM 'true'"), db::DatabaseError);
    EXPECT_THROW(connection.exec("COPY (SELECT 1) TO '/tmp/lineloc-copy-to-file'"),
                 db::DatabaseError);
    EXPECT_THROW(connection.exec("ALTER ROLE lineloc_reader SUPERUSER"), db::DatabaseError);
  }
}

}  // namespace
}  // namespace lineloc
