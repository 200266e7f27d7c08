#include "db/enrichment_store.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <set>
#include <stdexcept>

#include "common/geometry/line_segments.h"

namespace lineloc::db {
namespace {

constexpr int64_t kNanosecondsPerMicrosecond = 1000;

std::string number(double value) {
  return fmt::format("{:.17g}", value);
}

std::string arrayOf(const Eigen::Matrix3d& matrix) {
  std::vector<std::string> values;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      values.push_back(number(matrix(r, c)));
    }
  }
  return fmt::format("{{{}}}", fmt::join(values, ","));
}

std::string arrayOf(const Eigen::Vector3d& vector) {
  return fmt::format("{{{},{},{}}}", number(vector.x()), number(vector.y()), number(vector.z()));
}

// PostgreSQL's text form of a float8[]: {a,b,...}.
std::vector<double> parseArray(const std::string& text) {
  std::vector<double> values;
  size_t at = 1;
  while (at < text.size() && text[at] != '}') {
    size_t used = 0;
    values.push_back(std::stod(text.substr(at), &used));
    at += used;
    if (at < text.size() && text[at] == ',') {
      ++at;
    }
  }
  return values;
}

Eigen::Matrix3d matrixOf(const std::string& text) {
  const std::vector<double> values = parseArray(text);
  if (values.size() != 9) {
    throw DatabaseError("an enrichment covariance is not 9 numbers: " + text);
  }
  Eigen::Matrix3d matrix;
  for (int i = 0; i < 9; ++i) {
    matrix(i / 3, i % 3) = values[static_cast<size_t>(i)];
  }
  return matrix;
}

// Microseconds since the epoch, as SQL's to_timestamp wants them (seconds).
std::string timestamp(int64_t stamp_ns) {
  return fmt::format("{}.{:06d}", stamp_ns / 1'000'000'000,
                     (stamp_ns % 1'000'000'000) / kNanosecondsPerMicrosecond);
}

// The site-frame point whose CRS coordinates are columns column..column + 2.
Eigen::Vector3d sitePoint(const Result& result, int row, int column,
                          const Eigen::Vector3d& origin) {
  Eigen::Vector3d point;
  for (int axis = 0; axis < 3; ++axis) {
    point(axis) = std::stod(result.text(row, column + axis)) - origin(axis);
  }
  return point;
}

void validate(const EnrichmentSighting& sighting, size_t index) {
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument(fmt::format("enrichment sighting {}: {}", index, what));
  };
  if (!sighting.start_world.allFinite() || !sighting.end_world.allFinite() ||
      !sighting.start_covariance.allFinite() || !sighting.end_covariance.allFinite() ||
      !sighting.plane_normal.allFinite() || !std::isfinite(sighting.plane_offset)) {
    fail("a number is not finite");
  }
  if ((sighting.end_world - sighting.start_world).norm() < 1e-6) {
    fail("the line has no length");
  }
  if (std::abs(sighting.plane_normal.norm() - 1.0) > 1e-6) {
    fail("the plane's normal is not a unit vector");
  }
  if (sighting.robot.empty() || sighting.views <= 0) {
    fail("it names no robot or has no views");
  }
  if (sighting.last_seen_ns < sighting.first_seen_ns) {
    fail("it was last seen before it was first seen");
  }
}

// The stored line a sighting joins (see the header), or none.
struct NearLine {
  int64_t id = 0;
  Eigen::Vector3d start_world;
  Eigen::Vector3d end_world;
  double covariance_trace = 0.0;
};

class PassWriter {
 public:
  PassWriter(Connection& connection, const Site& site, const std::string& pass,
             const EnrichmentMergeOptions& options)
      : connection_(connection), site_(site), pass_(pass), options_(options) {}

  void write(const EnrichmentSighting& sighting, EnrichmentWriteReport& report) {
    const std::optional<NearLine> stored = nearestJoined(sighting);
    const int64_t line_id = stored ? stored->id : insertLine(sighting);
    seen_.insert(line_id);
    const bool recorded = insertSighting(line_id, sighting);
    if (!stored) {
      ++report.added;
      return;
    }
    if (!recorded) {
      ++report.already_written;
      return;
    }
    ++report.joined;
    updateLine(*stored, sighting);
    report.confirmed += confirmIfSeenOnEnoughPasses(line_id) ? 1 : 0;
  }

  // Records the miss of an expected line no sighting of the pass joined, now
  // or when the pass was written before (a pass written piecewise, as a
  // backbone writes a robot's day tile by tile), and retires the line when
  // enough passes since it was last seen missed it.
  void miss(const EnrichmentExpectation& expected, EnrichmentWriteReport& report) {
    if (seen_.count(expected.line_id) > 0) {
      return;
    }
    const Result missed = connection_.execParams(
        "INSERT INTO enrichment_miss (line_id, pass, missed_at) SELECT id, $2, to_timestamp($3) "
        "FROM enrichment_line WHERE id = $1 AND site_id = $4 AND status <> 2 AND NOT EXISTS "
        "(SELECT 1 FROM enrichment_sighting s WHERE s.line_id = $1 AND s.pass = $2) "
        "ON CONFLICT (line_id, pass) DO NOTHING RETURNING line_id",
        {std::to_string(expected.line_id), pass_, timestamp(expected.expected_at_ns),
         std::to_string(site_.id)});
    if (missed.rows() == 0) {
      return;
    }
    ++report.missed;
    const Result retired = connection_.execParams(
        "UPDATE enrichment_line l SET status = 2 WHERE id = $1 AND status <> 2 AND "
        "(SELECT count(*) FROM enrichment_miss m WHERE m.line_id = l.id AND m.missed_at > "
        "l.last_seen) >= $2 RETURNING id",
        {std::to_string(expected.line_id), std::to_string(options_.retire_after_passes)});
    report.retired += retired.rows();
  }

 private:
  Eigen::Vector3d crs(const Eigen::Vector3d& world) const { return world + site_.origin; }

  std::string pointSql(int first_parameter) const {
    return fmt::format("ST_MakePoint(${}, ${}, ${})", first_parameter, first_parameter + 1,
                       first_parameter + 2);
  }

  std::optional<NearLine> nearestJoined(const EnrichmentSighting& sighting) {
    const Eigen::Vector3d a = crs(sighting.start_world), b = crs(sighting.end_world);
    const Result result = connection_.execParams(
        "SELECT id, ST_X(ST_StartPoint(geom)), ST_Y(ST_StartPoint(geom)), "
        "ST_Z(ST_StartPoint(geom)), ST_X(ST_EndPoint(geom)), ST_Y(ST_EndPoint(geom)), "
        "ST_Z(ST_EndPoint(geom)), start_covariance[1] + start_covariance[5] + "
        "start_covariance[9] + end_covariance[1] + end_covariance[5] + end_covariance[9] "
        "FROM enrichment_line WHERE site_id = $1 AND status <> 2 AND geom &&& "
        "ST_Expand(ST_SetSRID(ST_MakeLine(" +
            pointSql(2) + ", " + pointSql(5) + "), $8), $9, $9, $9) ORDER BY id",
        {std::to_string(site_.id), number(a.x()), number(a.y()), number(a.z()), number(b.x()),
         number(b.y()), number(b.z()), std::to_string(site_.srid),
         number(options_.max_distance_m)});
    std::optional<NearLine> nearest;
    double nearest_m = std::numeric_limits<double>::infinity();
    for (int row = 0; row < result.rows(); ++row) {
      NearLine line;
      line.id = std::stoll(result.text(row, 0));
      line.start_world = sitePoint(result, row, 1, site_.origin);
      line.end_world = sitePoint(result, row, 4, site_.origin);
      line.covariance_trace = std::stod(result.text(row, 7));
      if (!runsAlong(line.start_world, line.end_world, sighting.start_world, sighting.end_world,
                     options_.max_angle_rad, options_.max_distance_m)) {
        continue;
      }
      const double distance_m = (0.5 * (line.start_world + line.end_world) -
                                 0.5 * (sighting.start_world + sighting.end_world))
                                    .norm();
      if (distance_m < nearest_m) {
        nearest_m = distance_m;
        nearest = line;
      }
    }
    return nearest;
  }

  int64_t insertLine(const EnrichmentSighting& sighting) {
    const Eigen::Vector3d a = crs(sighting.start_world), b = crs(sighting.end_world);
    const Result result = connection_.execParams(
        "INSERT INTO enrichment_line (site_id, building_id, geom, plane_normal, plane_offset, "
        "start_covariance, end_covariance, first_seen, last_seen) VALUES ($1, NULLIF($2, "
        "'')::bigint, "
        "ST_SetSRID(ST_MakeLine(" +
            pointSql(3) + ", " + pointSql(6) +
            "), $9), $10, $11, $12, $13, to_timestamp($14), to_timestamp($15)) RETURNING id",
        {std::to_string(site_.id),
         sighting.building_id ? std::to_string(*sighting.building_id) : std::string(),
         number(a.x()), number(a.y()), number(a.z()), number(b.x()), number(b.y()), number(b.z()),
         std::to_string(site_.srid), arrayOf(sighting.plane_normal), number(sighting.plane_offset),
         arrayOf(sighting.start_covariance), arrayOf(sighting.end_covariance),
         timestamp(sighting.first_seen_ns), timestamp(sighting.last_seen_ns)});
    return std::stoll(result.text(0, 0));
  }

  // False when this pass's robot had already recorded a sighting of the line.
  bool insertSighting(int64_t line_id, const EnrichmentSighting& sighting) {
    const Result result = connection_.execParams(
        "INSERT INTO enrichment_sighting (line_id, pass, robot, views, first_seen, last_seen) "
        "VALUES ($1, $2, $3, $4, to_timestamp($5), to_timestamp($6)) "
        "ON CONFLICT (line_id, pass, robot) DO NOTHING RETURNING line_id",
        {std::to_string(line_id), pass_, sighting.robot, std::to_string(sighting.views),
         timestamp(sighting.first_seen_ns), timestamp(sighting.last_seen_ns)});
    return result.rows() == 1;
  }

  // The union of both extents along the more precise of the two lines.
  void updateLine(const NearLine& stored, const EnrichmentSighting& sighting) {
    const double sighted_trace =
        sighting.start_covariance.trace() + sighting.end_covariance.trace();
    const bool sighting_better = sighted_trace < stored.covariance_trace;
    const Eigen::Vector3d origin = sighting_better ? sighting.start_world : stored.start_world;
    const Eigen::Vector3d direction = sighting_better
                                          ? (sighting.end_world - sighting.start_world).normalized()
                                          : (stored.end_world - stored.start_world).normalized();
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (const Eigen::Vector3d& point :
         {stored.start_world, stored.end_world, sighting.start_world, sighting.end_world}) {
      const double along = direction.dot(point - origin);
      low = std::min(low, along);
      high = std::max(high, along);
    }
    const Eigen::Vector3d a = crs(origin + low * direction), b = crs(origin + high * direction);
    std::vector<std::string> parameters = {std::to_string(stored.id),
                                           number(a.x()),
                                           number(a.y()),
                                           number(a.z()),
                                           number(b.x()),
                                           number(b.y()),
                                           number(b.z()),
                                           std::to_string(site_.srid),
                                           timestamp(sighting.first_seen_ns),
                                           timestamp(sighting.last_seen_ns)};
    std::string better;
    if (sighting_better) {
      better =
          ", start_covariance = $11, end_covariance = $12, plane_normal = $13, "
          "plane_offset = $14";
      parameters.insert(parameters.end(),
                        {arrayOf(sighting.start_covariance), arrayOf(sighting.end_covariance),
                         arrayOf(sighting.plane_normal), number(sighting.plane_offset)});
    }
    connection_.execParams("UPDATE enrichment_line SET geom = ST_SetSRID(ST_MakeLine(" +
                               pointSql(2) + ", " + pointSql(5) +
                               "), $8), first_seen = least(first_seen, to_timestamp($9)), "
                               "last_seen = greatest(last_seen, to_timestamp($10))" +
                               better + " WHERE id = $1",
                           parameters);
  }

  bool confirmIfSeenOnEnoughPasses(int64_t line_id) {
    const Result result = connection_.execParams(
        "UPDATE enrichment_line SET status = 1 WHERE id = $1 AND status = 0 AND "
        "(SELECT count(DISTINCT pass) FROM enrichment_sighting WHERE line_id = $1) >= $2 "
        "RETURNING id",
        {std::to_string(line_id), std::to_string(options_.min_passes)});
    return result.rows() == 1;
  }

  Connection& connection_;
  const Site& site_;
  const std::string& pass_;
  const EnrichmentMergeOptions& options_;
  // The lines the pass's sightings joined or added.
  std::set<int64_t> seen_;
};

// The WHERE clause of a filter over enrichment_line l, and its parameters
// after the site's id ($1).
struct FilterSql {
  std::string where;
  std::vector<std::string> parameters;
};

FilterSql filterSql(const Site& site, const EnrichmentFilter& filter) {
  FilterSql sql{"l.site_id = $1", {std::to_string(site.id)}};
  const auto next = [&](const std::string& value) {
    sql.parameters.push_back(value);
    return fmt::format("${}", sql.parameters.size());
  };
  if (filter.status) {
    sql.where += " AND l.status = " + next(std::to_string(static_cast<int>(*filter.status)));
  }
  if (filter.area_world) {
    const Eigen::Vector2d low = filter.area_world->min() + site.origin.head<2>();
    const Eigen::Vector2d high = filter.area_world->max() + site.origin.head<2>();
    sql.where += fmt::format(" AND l.geom && ST_MakeEnvelope({}, {}, {}, {}, {})",
                             next(number(low.x())), next(number(low.y())), next(number(high.x())),
                             next(number(high.y())), next(std::to_string(site.srid)));
  }
  if (filter.seen_before_ns) {
    sql.where += " AND l.last_seen < to_timestamp(" + next(timestamp(*filter.seen_before_ns)) + ")";
  }
  if (filter.seen_after_ns) {
    sql.where += " AND l.first_seen > to_timestamp(" + next(timestamp(*filter.seen_after_ns)) + ")";
  }
  if (filter.pass) {
    sql.where +=
        " AND EXISTS (SELECT 1 FROM enrichment_sighting s WHERE s.line_id = l.id AND "
        "s.pass = " +
        next(*filter.pass) + ")";
  }
  if (filter.robot) {
    sql.where +=
        " AND EXISTS (SELECT 1 FROM enrichment_sighting s WHERE s.line_id = l.id AND "
        "s.robot = " +
        next(*filter.robot) + ")";
  }
  return sql;
}

int64_t nanosecondsOf(const std::string& epoch_seconds) {
  return std::llround(std::stod(epoch_seconds) * 1e6) * kNanosecondsPerMicrosecond;
}

}  // namespace

std::string toString(EnrichmentStatus status) {
  switch (status) {
    case EnrichmentStatus::kCandidate:
      return "candidate";
    case EnrichmentStatus::kConfirmed:
      return "confirmed";
    case EnrichmentStatus::kRetired:
      return "retired";
  }
  return "unknown";
}

EnrichmentStatus parseEnrichmentStatus(const std::string& name) {
  for (const EnrichmentStatus status :
       {EnrichmentStatus::kCandidate, EnrichmentStatus::kConfirmed, EnrichmentStatus::kRetired}) {
    if (toString(status) == name) {
      return status;
    }
  }
  throw std::invalid_argument(
      fmt::format("enrichment status '{}' is none of candidate, confirmed, retired", name));
}

EnrichmentWriteReport writeEnrichmentPass(Connection& connection, const Site& site,
                                          const std::string& pass,
                                          const std::vector<EnrichmentSighting>& sightings,
                                          const std::vector<EnrichmentExpectation>& expected,
                                          const EnrichmentMergeOptions& options) {
  if (pass.empty()) {
    throw std::invalid_argument("an enrichment pass needs a name (a drive or a day)");
  }
  for (size_t i = 0; i < sightings.size(); ++i) {
    validate(sightings[i], i);
  }
  EnrichmentWriteReport report;
  inTransaction(connection, [&] {
    // One writer per site at a time, so that two passes seeing one new line
    // do not both add it.
    connection.execParams("SELECT pg_advisory_xact_lock(hashtext('lineloc enrichment'), $1)",
                          {std::to_string(site.id)});
    PassWriter writer(connection, site, pass, options);
    for (const EnrichmentSighting& sighting : sightings) {
      writer.write(sighting, report);
    }
    for (const EnrichmentExpectation& expectation : expected) {
      writer.miss(expectation, report);
    }
  });
  return report;
}

std::vector<StoredEnrichmentLine> readEnrichment(Connection& connection, const Site& site,
                                                 const EnrichmentFilter& filter) {
  const FilterSql sql = filterSql(site, filter);
  const Result result = connection.execParams(
      "SELECT l.id, l.building_id, ST_X(ST_StartPoint(l.geom)), ST_Y(ST_StartPoint(l.geom)), "
      "ST_Z(ST_StartPoint(l.geom)), ST_X(ST_EndPoint(l.geom)), ST_Y(ST_EndPoint(l.geom)), "
      "ST_Z(ST_EndPoint(l.geom)), l.start_covariance, l.end_covariance, l.plane_normal, "
      "l.plane_offset, l.status, extract(epoch FROM l.first_seen), extract(epoch FROM "
      "l.last_seen), (SELECT count(DISTINCT pass) FROM enrichment_sighting s WHERE s.line_id = "
      "l.id), (SELECT count(DISTINCT robot) FROM enrichment_sighting s WHERE s.line_id = l.id), "
      "(SELECT coalesce(sum(views), 0) FROM enrichment_sighting s WHERE s.line_id = l.id) "
      "FROM enrichment_line l WHERE " +
          sql.where + " ORDER BY l.id",
      sql.parameters);
  std::vector<StoredEnrichmentLine> lines;
  for (int row = 0; row < result.rows(); ++row) {
    StoredEnrichmentLine line;
    line.id = std::stoll(result.text(row, 0));
    if (!result.isNull(row, 1)) {
      line.building_id = std::stoll(result.text(row, 1));
    }
    line.start_world = sitePoint(result, row, 2, site.origin);
    line.end_world = sitePoint(result, row, 5, site.origin);
    line.start_covariance = matrixOf(result.text(row, 8));
    line.end_covariance = matrixOf(result.text(row, 9));
    const std::vector<double> normal = parseArray(result.text(row, 10));
    line.plane_normal = Eigen::Vector3d(normal.at(0), normal.at(1), normal.at(2));
    line.plane_offset = std::stod(result.text(row, 11));
    line.status = static_cast<EnrichmentStatus>(std::stoi(result.text(row, 12)));
    line.first_seen_ns = nanosecondsOf(result.text(row, 13));
    line.last_seen_ns = nanosecondsOf(result.text(row, 14));
    line.passes = std::stoi(result.text(row, 15));
    line.robots = std::stoi(result.text(row, 16));
    line.views = std::stoi(result.text(row, 17));
    lines.push_back(line);
  }
  return lines;
}

int purgeEnrichment(Connection& connection, const Site& site, const EnrichmentFilter& filter) {
  const FilterSql sql = filterSql(site, filter);
  return connection
      .execParams("DELETE FROM enrichment_line l WHERE " + sql.where + " RETURNING l.id",
                  sql.parameters)
      .rows();
}

}  // namespace lineloc::db
