#include "db/model_line_query.h"

#include <fmt/format.h>

#include <algorithm>

#include "db/ewkb.h"
#include "db/line_pack.h"
#include "db/view_frustum.h"

namespace lineloc::db {
namespace {

constexpr const char* kStatement = "lineloc_line_packs_meeting";

// $1 site id, $2..$5 xmin ymin xmax ymax in site CRS coordinates.
constexpr const char* kSql = R"sql(
SELECT building_id, lines
FROM building_line_pack
WHERE site_id = $1::int4
  AND bounds && box(point($2::float8, $3::float8), point($4::float8, $5::float8))
)sql";

// Squared distance from p to the segment a-b.
double squaredDistanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).squaredNorm();
}

std::string number(double value) {
  return fmt::format("{:.17g}", value);
}

}  // namespace

ModelLineQuery::ModelLineQuery(Connection& connection, const Site& site)
    : connection_(connection), site_(site) {
  connection_.prepareOnce(kStatement, kSql);
}

std::vector<ModelLine> ModelLineQuery::linesOfBuildingsMeeting(
    const Eigen::AlignedBox2d& bounds_world) {
  const Eigen::Vector2d low = bounds_world.min() + site_.origin.head<2>();
  const Eigen::Vector2d high = bounds_world.max() + site_.origin.head<2>();
  const Result result =
      connection_.execPrepared(kStatement,
                               {std::to_string(site_.id), number(low.x()), number(low.y()),
                                number(high.x()), number(high.y())},
                               true);
  size_t pack_bytes = 0;
  for (int row = 0; row < result.rows(); ++row) {
    pack_bytes += static_cast<size_t>(result.length(row, 1));
  }
  std::vector<ModelLine> lines;
  lines.reserve(pack_bytes / kLinePackRecordBytes);
  for (int row = 0; row < result.rows(); ++row) {
    decodeLinePack({result.bytes(row, 1), static_cast<size_t>(result.length(row, 1))},
                   result.binaryInt8(row, 0), site_.origin, lines);
  }
  return lines;
}

std::vector<ModelLine> ModelLineQuery::linesWithin(const Eigen::Vector3d& center_world,
                                                   double radius_m) {
  const Eigen::Vector2d reach = Eigen::Vector2d::Constant(radius_m);
  std::vector<ModelLine> lines =
      linesOfBuildingsMeeting({center_world.head<2>() - reach, center_world.head<2>() + reach});
  const double radius2 = radius_m * radius_m;
  std::erase_if(lines, [&](const ModelLine& line) {
    return squaredDistanceToSegment(center_world, line.start_world, line.end_world) > radius2;
  });
  return lines;
}

std::vector<ModelLine> ModelLineQuery::linesInFrustum(const Eigen::Isometry3d& T_world_camera,
                                                      const PinholeCamera& camera, double near_m,
                                                      double far_m) {
  const ViewFrustum frustum(T_world_camera, camera, near_m, far_m);
  const Eigen::AlignedBox3d& bounds = frustum.boundsWorld();
  std::vector<ModelLine> lines =
      linesOfBuildingsMeeting({bounds.min().head<2>(), bounds.max().head<2>()});
  std::erase_if(lines, [&](const ModelLine& line) {
    return !frustum.meetsSegment(line.start_world, line.end_world);
  });
  return lines;
}

}  // namespace lineloc::db
