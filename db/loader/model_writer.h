// Writes a validated city model with its extracted lines and its terrain into
// a site, in the caller's transaction: the source's previous buildings (and
// through them their faces and lines) and terrain are replaced, never duplicated, and nothing is
// written when the same file was already loaded with the same options. Rows
// go in through binary COPY (geometry as EWKB), building and line ids reserved
// up front so faces, lines and each building's line pack (db/line_pack.h)
// reference them without a round trip per row.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "db/citymodel/city_model.h"
#include "db/citymodel/line_extraction.h"
#include "db/connection.h"
#include "db/site.h"

namespace lineloc::db {

struct SourceRecord {
  std::string name;     // the source's name in the database (its file name)
  std::string hash;     // SHA-256 of its bytes, hex
  std::string options;  // the load options that shape what is stored
};

struct WriteSummary {
  bool unchanged = false;  // same hash and options as the stored version: nothing written
  int buildings = 0;
  int faces = 0;
  int lines = 0;
  int terrain_triangles = 0;
};

// `lines[i]` are the lines of `buildings[i]`, in the site's CRS like the faces
// and the `terrain`, which replaces the source's terrain triangles.
// `progress(done)` is called as buildings are written. Must run inside a
// transaction (see inTransaction) so a failure leaves the database as it was.
WriteSummary writeModel(Connection& connection, const Site& site, const SourceRecord& source,
                        const std::vector<citymodel::Building>& buildings,
                        const std::vector<std::vector<citymodel::ExtractedLine>>& lines,
                        const std::vector<citymodel::TerrainTriangle>& terrain,
                        const std::function<void(size_t)>& progress);

}  // namespace lineloc::db
