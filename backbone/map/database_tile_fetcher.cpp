#include "backbone/map/database_tile_fetcher.h"

#include <libpq-fe.h>

#include <memory>

#include "db/site.h"

namespace lineloc {
namespace {

// A connection and the tile query on it.
struct Session {
  Session(const std::string& conninfo, const std::string& site_name, bool learnt_lines)
      : connection(conninfo),
        query(connection, db::requireSite(connection, site_name), learnt_lines) {}

  db::Connection connection;
  db::MapTileQuery query;
};

}  // namespace

TileFetcher makeDatabaseTileFetcher(const std::string& conninfo, const std::string& site_name,
                                    bool learnt_lines) {
  auto session = std::make_shared<std::unique_ptr<Session>>(
      std::make_unique<Session>(conninfo, site_name, learnt_lines));
  return [session, conninfo, site_name, learnt_lines](const Eigen::AlignedBox2d& bounds_world) {
    try {
      return (*session)->query.within(bounds_world);
    } catch (const db::DatabaseError&) {
      if (PQstatus((*session)->connection.get()) == CONNECTION_OK) {
        throw;
      }
      // The server went away: connect again, to the next server the
      // connection string names that answers, and ask once more.
      *session = std::make_unique<Session>(conninfo, site_name, learnt_lines);
      return (*session)->query.within(bounds_world);
    }
  };
}

}  // namespace lineloc
