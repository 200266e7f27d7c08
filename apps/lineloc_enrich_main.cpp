// lineloc-enrich: lines learnt from a recorded drive for the city model,
// offline (apps/offline_enrichment.h).
#include <spdlog/spdlog.h>

#include <iostream>

#include "apps/offline_enrichment.h"
#include "common/config/program_options.h"

int main(int argc, char** argv) {
  lineloc::OfflineEnrichmentConfig config;
  lineloc::ProgramOptions options(
      "lineloc-enrich", "Lines learnt for a city model from a recorded drive and its fix log");
  lineloc::addRecordedDriveOptions(options, config.drive);
  options.add("fix_log", config.fix_log, "the robot's log of the backbone's answers (fixes.txt)");
  options.add("out", config.out, "learnt lines written");
  options.add("robot", config.robot, "the robot that drove, named in the sightings");
  options.add("db", config.db,
              "libpq connection string of the database to store the lines in, as "
              "lineloc_enricher (empty: not stored)");
  options.add("site", config.site, "with --db: the site the city model is");
  options.add("pass", config.pass,
              "with --db: the drive or day the lines were seen on; a second pass confirms them");
  options.add("max_placement_sigma_m", config.learner.observation.max_placement_sigma_m,
              "segments the fix places on a wall less precisely than this are not learnt from "
              "(m, across the line)");
  options.add("min_views", config.learner.tracks.triangulation.min_views,
              "views a line needs before it is triangulated");
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  try {
    lineloc::runOfflineEnrichment(config, std::cout);
    return 0;
  } catch (const std::exception& error) {
    spdlog::error("{}", error.what());
    return 1;
  }
}
