#include "backbone/map/database_tile_fetcher.h"

#include <fmt/format.h>

#include <memory>

#include "db/site.h"

namespace lineloc {

TileFetcher makeDatabaseTileFetcher(const std::string& conninfo, const std::string& site_name) {
  auto connection = std::make_shared<db::Connection>(conninfo);
  const std::optional<db::Site> site = db::findSite(*connection, site_name);
  if (!site) {
    throw db::DatabaseError(fmt::format("site '{}' is not in the database", site_name));
  }
  auto query = std::make_shared<db::MapTileQuery>(*connection, *site);
  return [connection, query](const Eigen::AlignedBox2d& bounds_world) {
    return query->within(bounds_world);
  };
}

}  // namespace lineloc
