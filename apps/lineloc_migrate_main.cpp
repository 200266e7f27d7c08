// lineloc-migrate: brings a lineloc database to the newest schema.
#include <fmt/format.h>

#include <iostream>

#include "common/config/program_options.h"
#include "db/migrations.h"

int main(int argc, char** argv) {
  std::string conninfo = "host=127.0.0.1 port=55432 user=lineloc_owner dbname=lineloc";
  lineloc::ProgramOptions options("lineloc-migrate",
                                  "Apply lineloc's schema migrations to a PostGIS database");
  options.add("db", conninfo, "libpq connection string of the database, as its owner role");
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  try {
    lineloc::db::Connection connection(conninfo);
    const int applied = lineloc::db::applyMigrations(connection, lineloc::db::embeddedMigrations());
    std::cout << fmt::format("lineloc-migrate: applied {} migration(s), schema version {}\n",
                             applied, lineloc::db::schemaVersion(connection));
    return 0;
  } catch (const std::exception& error) {
    std::cerr << "lineloc-migrate: " << error.what() << '\n';
    return 1;
  }
}
