#include "db/tiles/map_tile_query.h"

#include <fmt/format.h>

#include <algorithm>

#include "common/geometry/pose.h"
#include "db/enrichment_store.h"
#include "db/ewkb.h"

namespace lineloc::db {
namespace {

constexpr const char* kFacesStatement = "lineloc_tile_faces";

// $1 site, $2..$5 xmin ymin xmax ymax (site CRS). The 2D GiST index answers &&
// (bounding boxes overlap; the envelope's SRID does not matter to &&).
constexpr const char* kFacesSql = R"sql(
SELECT id, building_id, kind, geom
FROM face
WHERE site_id = $1::int4
  AND geom && ST_MakeEnvelope($2::float8, $3::float8, $4::float8, $5::float8)
)sql";

constexpr const char* kTerrainStatement = "lineloc_tile_terrain";

// $1 site, $2..$5 as above.
constexpr const char* kTerrainSql = R"sql(
SELECT id, geom
FROM terrain_triangle
WHERE site_id = $1::int4
  AND geom && ST_MakeEnvelope($2::float8, $3::float8, $4::float8, $5::float8)
)sql";

std::string number(double value) {
  return fmt::format("{:.17g}", value);
}

}  // namespace

MapTileQuery::MapTileQuery(Connection& connection, const Site& site, bool learnt_lines)
    : connection_(connection), site_(site), lines_(connection, site), learnt_lines_(learnt_lines) {
  connection_.prepareOnce(kFacesStatement, kFacesSql);
  connection_.prepareOnce(kTerrainStatement, kTerrainSql);
}

TileContents MapTileQuery::within(const Eigen::AlignedBox2d& bounds_world) {
  const Eigen::Vector2d low = bounds_world.min() + site_.origin.head<2>();
  const Eigen::Vector2d high = bounds_world.max() + site_.origin.head<2>();
  const std::vector<std::string> params = {std::to_string(site_.id), number(low.x()),
                                           number(low.y()), number(high.x()), number(high.y())};
  TileContents contents;
  contents.lines = lines_.linesOfBuildingsMeeting(bounds_world);
  const Result faces = connection_.execPrepared(kFacesStatement, params, true);
  for (int row = 0; row < faces.rows(); ++row) {
    const auto rings = decodeEwkbZ(faces.bytes(row, 3), faces.length(row, 3));
    if (!rings || rings->empty() || rings->front().size() < 4) {
      throw DatabaseError(fmt::format("face {} is not a polygon Z", faces.binaryInt8(row, 0)));
    }
    ModelFaceRecord face;
    face.id = faces.binaryInt8(row, 0);
    face.building_id = faces.binaryInt8(row, 1);
    face.kind = faces.binaryInt2(row, 2);
    const std::vector<Eigen::Vector3d>& closed = rings->front();
    for (size_t i = 0; i + 1 < closed.size(); ++i) {
      face.ring_world.push_back(closed[i] - site_.origin);
    }
    contents.faces.push_back(std::move(face));
  }
  const Result terrain = connection_.execPrepared(kTerrainStatement, params, true);
  contents.terrain.reserve(static_cast<size_t>(terrain.rows()));
  for (int row = 0; row < terrain.rows(); ++row) {
    const auto rings = decodeEwkbZ(terrain.bytes(row, 1), terrain.length(row, 1));
    if (!rings || rings->size() != 1 || rings->front().size() != 4) {
      throw DatabaseError(
          fmt::format("terrain triangle {} is not a triangle Z", terrain.binaryInt8(row, 0)));
    }
    const std::vector<Eigen::Vector3d>& closed = rings->front();
    contents.terrain.push_back(
        {terrain.binaryInt8(row, 0),
         {closed[0] - site_.origin, closed[1] - site_.origin, closed[2] - site_.origin}});
  }
  if (learnt_lines_) {
    EnrichmentFilter confirmed;
    confirmed.status = EnrichmentStatus::kConfirmed;
    confirmed.area_world = bounds_world;
    for (const StoredEnrichmentLine& line : readEnrichment(connection_, site_, confirmed)) {
      contents.learnt_lines.push_back(
          {line.id, line.start_world, line.end_world,
           std::max(largestSigma(line.start_covariance), largestSigma(line.end_covariance))});
    }
  }
  return contents;
}

}  // namespace lineloc::db
