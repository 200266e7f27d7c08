// Writes a site's stored lines back out for viewing: Wavefront OBJ (site-local
// coordinates, one `l` element per line, grouped by line kind) or GeoJSON
// (LineString features in the site's CRS, with kind and building id). With a
// filter, the site's learnt lines it takes follow (db/enrichment_store.h), of
// kind "learnt", in GeoJSON with their status and passes too.
#pragma once

#include <optional>
#include <string>

#include "db/connection.h"
#include "db/enrichment_store.h"
#include "db/site.h"

namespace lineloc::db {

// Format from the extension of `path` (.obj, .geojson or .json); returns the
// number of lines written. Throws std::runtime_error naming the file.
int exportLines(Connection& connection, const Site& site, const std::string& path,
                const std::optional<EnrichmentFilter>& learnt = std::nullopt);

}  // namespace lineloc::db
