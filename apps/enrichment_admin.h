// What lineloc-enrichment does: lists, exports and purges a site's learnt
// lines (db/enrichment_store.h) by status, area, time, pass or robot.
//   list    one row per line: id, status, passes, robots, views, first and
//           last seen (UTC), length, the largest standard deviation of its
//           ends;
//   export  the learnt line file (apps/learnt_line_file.h) to `out`;
//   purge   deletes them with their sightings; refused without a filter
//           unless `all` is set, so that a forgotten option does not empty a
//           site.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace lineloc {

struct EnrichmentAdminConfig {
  // list, export or purge.
  std::string action = "list";
  // libpq connection string: the reader's suffices to list and export, a
  // purge needs the enricher's.
  std::string db;
  std::string site;
  // Filters; empty: any. Area: x0 y0 x1 y1 in the site frame (m); times UTC
  // (2026-04-14T09:30:00Z).
  std::string status;
  std::vector<double> area;
  std::string seen_before;
  std::string seen_after;
  std::string pass;
  std::string robot;
  bool all = false;
  // export: the file written.
  std::string out = "enrichment.txt";
};

// Returns the number of lines listed, exported or purged. Throws
// std::runtime_error or std::invalid_argument naming the option that is
// malformed, and db::DatabaseError when the database refuses.
int runEnrichmentAdmin(const EnrichmentAdminConfig& config, std::ostream& out);

}  // namespace lineloc
