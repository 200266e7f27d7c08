// lineloc-enrichment: a site's learnt lines listed, exported or purged
// (apps/enrichment_admin.h).
#include <spdlog/spdlog.h>

#include <iostream>

#include "apps/enrichment_admin.h"
#include "common/config/program_options.h"

int main(int argc, char** argv) {
  lineloc::EnrichmentAdminConfig config;
  lineloc::ProgramOptions options("lineloc-enrichment",
                                  "A site's learnt lines listed, exported or purged");
  options.add("action", config.action, "list, export or purge");
  options.add("db", config.db,
              "libpq connection string (lineloc_reader to list and export, lineloc_enricher to "
              "purge)");
  options.add("site", config.site, "the site whose learnt lines");
  options.add("status", config.status, "only lines of this status: candidate, confirmed, retired");
  options.addFixedSize("area", config.area, 4,
                       "only lines that touch the box x0 y0 x1 y1 (m, site frame)");
  options.add("seen_before", config.seen_before,
              "only lines last seen before this UTC time (2026-04-14T09:30:00Z)");
  options.add("seen_after", config.seen_after, "only lines first seen after this UTC time");
  options.add("pass", config.pass, "only lines a sighting of this pass supports");
  options.add("robot", config.robot, "only lines a sighting of this robot supports");
  options.addFlag("all", config.all, "purge: every learnt line of the site, no filter needed");
  options.add("out", config.out, "export: the learnt line file written");
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  try {
    lineloc::runEnrichmentAdmin(config, std::cout);
    return 0;
  } catch (const std::exception& error) {
    spdlog::error("{}", error.what());
    return 1;
  }
}
