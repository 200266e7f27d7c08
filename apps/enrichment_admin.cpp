#include "apps/enrichment_admin.h"

#include <fmt/format.h>

#include <ostream>
#include <stdexcept>

#include "apps/learnt_line_file.h"
#include "common/geometry/pose.h"
#include "common/time/utc_time.h"
#include "db/connection.h"
#include "db/enrichment_store.h"
#include "db/site.h"

namespace lineloc {
namespace {

db::EnrichmentFilter filterOf(const EnrichmentAdminConfig& config) {
  db::EnrichmentFilter filter;
  if (!config.status.empty()) {
    filter.status = db::parseEnrichmentStatus(config.status);
  }
  if (!config.area.empty()) {
    if (config.area.size() != 4) {
      throw std::invalid_argument("--area takes x0 y0 x1 y1 (m, site frame)");
    }
    filter.area_world = Eigen::AlignedBox2d(Eigen::Vector2d(config.area[0], config.area[1]))
                            .extend(Eigen::Vector2d(config.area[2], config.area[3]));
  }
  if (!config.seen_before.empty()) {
    filter.seen_before_ns = parseUtcTime_ns(config.seen_before);
  }
  if (!config.seen_after.empty()) {
    filter.seen_after_ns = parseUtcTime_ns(config.seen_after);
  }
  if (!config.pass.empty()) {
    filter.pass = config.pass;
  }
  if (!config.robot.empty()) {
    filter.robot = config.robot;
  }
  return filter;
}

bool filters(const db::EnrichmentFilter& filter) {
  return filter.status || filter.area_world || filter.seen_before_ns || filter.seen_after_ns ||
         filter.pass || filter.robot;
}

void list(const std::vector<db::StoredEnrichmentLine>& lines, std::ostream& out) {
  out << fmt::format("{:>8} {:>9} {:>6} {:>6} {:>6} {:>24} {:>24} {:>8} {:>8}\n", "id", "status",
                     "passes", "robots", "views", "first_seen", "last_seen", "length_m", "sigma_m");
  for (const db::StoredEnrichmentLine& line : lines) {
    out << fmt::format(
        "{:>8} {:>9} {:>6} {:>6} {:>6} {:>24} {:>24} {:>8.3f} {:>8.4f}\n", line.id,
        db::toString(line.status), line.passes, line.robots, line.views,
        formatUtcTime(line.first_seen_ns), formatUtcTime(line.last_seen_ns),
        (line.end_world - line.start_world).norm(),
        std::max(largestSigma(line.start_covariance), largestSigma(line.end_covariance)));
  }
}

}  // namespace

int runEnrichmentAdmin(const EnrichmentAdminConfig& config, std::ostream& out) {
  if (config.db.empty() || config.site.empty()) {
    throw std::invalid_argument("--db and --site are required");
  }
  if (config.action != "list" && config.action != "export" && config.action != "purge") {
    throw std::invalid_argument(
        fmt::format("--action '{}' is none of list, export, purge", config.action));
  }
  const db::EnrichmentFilter filter = filterOf(config);
  db::Connection connection(config.db);
  const db::Site site = db::requireSite(connection, config.site);
  if (config.action == "purge") {
    if (!filters(filter) && !config.all) {
      throw std::invalid_argument(
          "a purge without --status, --area, --seen-before, --seen-after, --pass or --robot "
          "deletes every learnt line of the site: give --all to mean it");
    }
    const int purged = db::purgeEnrichment(connection, site, filter);
    out << fmt::format("lineloc-enrichment: purged {} learnt lines of site '{}'\n", purged,
                       site.name);
    return purged;
  }
  const std::vector<db::StoredEnrichmentLine> lines = db::readEnrichment(connection, site, filter);
  if (config.action == "list") {
    list(lines, out);
    return static_cast<int>(lines.size());
  }
  std::vector<LearntLineRow> rows;
  for (const db::StoredEnrichmentLine& line : lines) {
    rows.push_back({line.start_world, line.end_world, line.building_id.value_or(-1), line.views,
                    line.robots, line.start_covariance, line.end_covariance});
  }
  writeLearntLineFile(config.out, rows);
  out << fmt::format("lineloc-enrichment: {} learnt lines of site '{}' -> {}\n", rows.size(),
                     site.name, config.out);
  return static_cast<int>(rows.size());
}

}  // namespace lineloc
