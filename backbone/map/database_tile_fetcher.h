// Map tiles read from the PostGIS building database (db/tiles), for the tile
// cache's worker thread: the fetcher owns its own connection.
#pragma once

#include <string>

#include "backbone/map/map_tile_cache.h"

namespace lineloc {

// Connects to `conninfo` and finds site `site_name` now; throws
// db::DatabaseError when either fails. A fetch whose server has gone away
// connects again and asks once more: with a connection string that names
// several servers (a replica, then its primary; docs/production.md), the
// next that answers. With `learnt_lines`, tiles hold the site's confirmed
// learnt lines too.
TileFetcher makeDatabaseTileFetcher(const std::string& conninfo, const std::string& site_name,
                                    bool learnt_lines = false);

}  // namespace lineloc
