#include "db/model_line_query.h"

#include <fmt/format.h>

namespace lineloc::db {
namespace {

constexpr const char* kStatement = "lineloc_lines_within";

// $1 site id, $2..$4 centre in site CRS coordinates, $5 radius, $6 SRID.
// The &&& box test selects candidates through the n-D GiST index; the exact
// 3D distance test then keeps those really within the radius.
constexpr const char* kSql = R"sql(
WITH centre AS (SELECT ST_SetSRID(ST_MakePoint($2::float8, $3::float8, $4::float8), $6::int4) AS p,
                       $5::float8 AS r)
SELECT l.id, l.building_id, l.kind,
       ST_X(ST_StartPoint(l.geom)), ST_Y(ST_StartPoint(l.geom)), ST_Z(ST_StartPoint(l.geom)),
       ST_X(ST_EndPoint(l.geom)), ST_Y(ST_EndPoint(l.geom)), ST_Z(ST_EndPoint(l.geom))
FROM line l, centre
WHERE l.site_id = $1::int4
  AND l.geom &&& ST_3DMakeBox(ST_Translate(centre.p, -centre.r, -centre.r, -centre.r),
                              ST_Translate(centre.p, centre.r, centre.r, centre.r))
  AND ST_3DDWithin(l.geom, centre.p, centre.r)
)sql";

std::string number(double value) {
  return fmt::format("{:.17g}", value);
}

}  // namespace

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
                                number(center.z()), number(radius_m), std::to_string(site_.srid)},
                               true);
  std::vector<ModelLine> lines(result.rows());
  for (int row = 0; row < result.rows(); ++row) {
    ModelLine& line = lines[row];
    line.id = result.binaryInt8(row, 0);
    line.building_id = result.binaryInt8(row, 1);
    line.kind = static_cast<LineKind>(result.binaryInt2(row, 2));
    line.start_world = Eigen::Vector3d(result.binaryFloat8(row, 3), result.binaryFloat8(row, 4),
                                       result.binaryFloat8(row, 5)) -
                       site_.origin;
    line.end_world = Eigen::Vector3d(result.binaryFloat8(row, 6), result.binaryFloat8(row, 7),
                                     result.binaryFloat8(row, 8)) -
                     site_.origin;
  }
  return lines;
}

}  // namespace lineloc::db
