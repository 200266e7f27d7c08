#include "backbone/map/database_tile_fetcher.h"

#include <memory>

#include "db/site.h"

namespace lineloc {

TileFetcher makeDatabaseTileFetcher(const std::string& conninfo, const std::string& site_name) {
  auto connection = std::make_shared<db::Connection>(conninfo);
  auto query =
      std::make_shared<db::MapTileQuery>(*connection, db::requireSite(*connection, site_name));
  return [connection, query](const Eigen::AlignedBox2d& bounds_world) {
    return query->within(bounds_world);
  };
}

}  // namespace lineloc
