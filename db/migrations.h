// Ordered schema migrations (db/migrations/NNNN_name.sql, embedded at build
// time), applied by a runner that records each applied version in
// schema_migrations. Re-running applies nothing new; each migration runs in
// its own transaction, under an advisory lock so concurrent runners serialise.
#pragma once

#include <string>
#include <vector>

#include "db/connection.h"

namespace lineloc::db {

struct Migration {
  int version;
  const char* name;
  const char* sql;
};

const std::vector<Migration>& embeddedMigrations();

// Applies the migrations not yet recorded; returns how many it applied.
// Throws DatabaseError naming the migration that failed (its changes are rolled back).
int applyMigrations(Connection& connection, const std::vector<Migration>& migrations);

// The highest applied version, 0 for an empty database. Reads only.
int schemaVersion(Connection& connection);

// Throws DatabaseError, telling to run lineloc-migrate as the owner role,
// unless the schema is at the newest of `migrations`: for programs whose role
// may not migrate (lineloc-load writes as the writer role).
void requireMigrated(Connection& connection, const std::vector<Migration>& migrations);

}  // namespace lineloc::db
