#include "db/model_line_query.h"

#include <fmt/format.h>

#include <algorithm>

#include "db/ewkb.h"

namespace lineloc::db {
namespace {

constexpr const char* kStatement = "lineloc_lines_within";

// $1 site id, $2..$4 centre in site CRS coordinates, $5 radius. The box needs no SRID (&&& compares
// boxes).
const std::string kSql = std::string("SELECT ") + kModelLineColumns + R"sql(
FROM line
WHERE site_id = $1::int4
  AND geom &&& ST_3DMakeBox(ST_MakePoint($2::float8 - $5::float8, $3::float8 - $5::float8,
                                         $4::float8 - $5::float8),
                            ST_MakePoint($2::float8 + $5::float8, $3::float8 + $5::float8,
                                         $4::float8 + $5::float8))
)sql";

// Squared distance from p to the segment a-b.
double squaredDistanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).squaredNorm();
}

Eigen::Vector3d optionalVector(const Result& result, int row, int column) {
  if (result.isNull(row, column)) {
    return Eigen::Vector3d::Zero();
  }
  return {result.binaryFloat8(row, column), result.binaryFloat8(row, column + 1),
          result.binaryFloat8(row, column + 2)};
}

int optionalOrdinal(const Result& result, int row, int column) {
  return result.isNull(row, column) ? -1 : result.binaryInt4(row, column);
}

std::string number(double value) {
  return fmt::format("{:.17g}", value);
}

}  // namespace

ModelLine decodeModelLine(const Result& result, int row, const Eigen::Vector3d& origin) {
  const auto points = decodeEwkbZ(result.bytes(row, 3), result.length(row, 3));
  if (!points || points->size() != 1 || points->front().size() != 2) {
    throw DatabaseError(
        fmt::format("line {}: geometry is not a 2-point LINESTRING Z", result.binaryInt8(row, 0)));
  }
  ModelLine line;
  line.id = result.binaryInt8(row, 0);
  line.building_id = result.binaryInt8(row, 1);
  line.kind = static_cast<LineKind>(result.binaryInt2(row, 2));
  line.start_world = points->front()[0] - origin;
  line.end_world = points->front()[1] - origin;
  line.face_a = optionalOrdinal(result, row, 4);
  line.face_b = optionalOrdinal(result, row, 5);
  line.normal_a = optionalVector(result, row, 6);
  line.normal_b = optionalVector(result, row, 9);
  return line;
}

ModelLineQuery::ModelLineQuery(Connection& connection, const Site& site)
    : connection_(connection), site_(site) {
  connection_.prepare(kStatement, kSql);
}

std::vector<ModelLine> ModelLineQuery::linesWithin(const Eigen::Vector3d& center_world,
                                                   double radius_m) {
  const Eigen::Vector3d center = center_world + site_.origin;
  const Result result =
      connection_.execPrepared(kStatement,
                               {std::to_string(site_.id), number(center.x()), number(center.y()),
                                number(center.z()), number(radius_m)},
                               true);
  const double radius2 = radius_m * radius_m;
  std::vector<ModelLine> lines;
  lines.reserve(result.rows());
  for (int row = 0; row < result.rows(); ++row) {
    ModelLine line = decodeModelLine(result, row, site_.origin);
    if (squaredDistanceToSegment(center_world, line.start_world, line.end_world) <= radius2) {
      lines.push_back(std::move(line));
    }
  }
  return lines;
}

}  // namespace lineloc::db
