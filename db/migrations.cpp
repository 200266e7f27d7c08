#include "db/migrations.h"

#include <fmt/format.h>

namespace lineloc::db {
namespace {

// Arbitrary constant naming lineloc's migration lock among advisory locks.
constexpr const char* kLockKey = "7391550241";

void ensureMigrationsTable(Connection& connection) {
  connection.exec(
      "CREATE TABLE IF NOT EXISTS schema_migrations ("
      " version integer PRIMARY KEY, name text NOT NULL,"
      " applied_at timestamptz NOT NULL DEFAULT now())");
}

bool isApplied(Connection& connection, int version) {
  return connection
             .execParams("SELECT 1 FROM schema_migrations WHERE version = $1",
                         {std::to_string(version)})
             .rows() > 0;
}

}  // namespace

int schemaVersion(Connection& connection) {
  if (connection.exec("SELECT to_regclass('schema_migrations') IS NULL").text(0, 0) == "t") {
    return 0;
  }
  return std::stoi(
      connection.exec("SELECT coalesce(max(version), 0) FROM schema_migrations").text(0, 0));
}

void requireMigrated(Connection& connection, const std::vector<Migration>& migrations) {
  const int version = schemaVersion(connection);
  const int newest = migrations.empty() ? 0 : migrations.back().version;
  if (version < newest) {
    throw DatabaseError(fmt::format(
        "the database's schema is at version {}, not {}: run lineloc-migrate as its owner role",
        version, newest));
  }
}

int applyMigrations(Connection& connection, const std::vector<Migration>& migrations) {
  connection.exec(fmt::format("SELECT pg_advisory_lock({})", kLockKey));
  int applied = 0;
  try {
    ensureMigrationsTable(connection);
    for (const Migration& migration : migrations) {
      if (isApplied(connection, migration.version)) {
        continue;
      }
      try {
        inTransaction(connection, [&] {
          connection.exec(migration.sql);
          connection.execParams("INSERT INTO schema_migrations (version, name) VALUES ($1, $2)",
                                {std::to_string(migration.version), migration.name});
        });
      } catch (const DatabaseError& error) {
        throw DatabaseError(fmt::format("migration {:04d}_{}: {}", migration.version,
                                        migration.name, error.what()));
      }
      ++applied;
    }
  } catch (...) {
    PQclear(
        PQexec(connection.get(), fmt::format("SELECT pg_advisory_unlock({})", kLockKey).c_str()));
    throw;
  }
  connection.exec(fmt::format("SELECT pg_advisory_unlock({})", kLockKey));
  return applied;
}

}  // namespace lineloc::db
