// lineloc-backbone: answers every robot's LineSet with a PoseFix.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <csignal>
#include <iostream>
#include <vector>

#include "backbone/service/backbone_service.h"
#include "common/config/option_values.h"
#include "common/config/program_options.h"
#include "common/parallel/resident_heap.h"

namespace {
std::atomic<bool> g_stop{false};
void requestStop(int) {
  g_stop = true;
}
}  // namespace

int main(int argc, char** argv) {
  lineloc::BackboneConfig config;
  lineloc::ProgramOptions options("lineloc-backbone", "lineloc backbone matching service");
  options.add("domain_id", config.domain_id, "DDS domain id");
  options.add("dds_config", config.dds_config,
              "Cyclone DDS XML configuration file, or several separated by commas, each adding "
              "to the ones before (empty: CYCLONEDDS_URI / defaults)");
  options.add("db", config.db,
              "libpq connection string of the building database, as its reader role");
  options.add("site", config.site, "name of the site in the database");
  options.add("use_learnt_lines", config.use_learnt_lines,
              "match the site's confirmed learnt lines (lineloc-enrich) with the model's, each "
              "weighted by its own uncertainty: true or false");
  options.add("learning_db", config.learning_db,
              "libpq connection string of the database as its enricher role: lines are learnt "
              "from the frames answered and stored as the site's enrichment (empty: none are); "
              "give it a connect_timeout");
  options.add("backbone_name", config.backbone_name,
              "this backbone's name among those sharing the domain's robots, "
              "[A-Za-z0-9][A-Za-z0-9_.-]* (empty: <hostname>-<pid>)");
  options.add("backbone_lease_s", config.backbone_lease_s,
              "a backbone silent this long (s) leaves its robots to the others");
  options.add("query_radius_m", config.query_radius_m,
              "model lines within this distance of the predicted position are used (m)");
  options.add("tile_size_m", config.tile_size_m, "side of the square map tiles cached (m)");
  options.add("max_cached_tiles", config.max_cached_tiles, "map tiles kept in memory");
  options.add("prefetch_lookahead_s", config.prefetch_lookahead_s,
              "map tiles are loaded where each robot will be this much later (s)");
  options.add("forget_robot_after_s", config.forget_robot_after_s,
              "a robot not heard from for this long is forgotten and served as new (s)");
  options.add("max_robots", config.max_robots,
              "robots served at once; the frames of others are answered busy until one is "
              "forgotten");
  options.add("max_queued_searches", config.max_queued_searches,
              "searches from a poor prediction waiting in all; a frame whose search finds them "
              "waiting is answered busy");
  options.add("answer_threads", config.answer_threads,
              "threads answering the LineSets of different robots at once (0: one per core); a "
              "frame that would be answered after its robot's next is answered busy at once");
  options.add("realtime_priority", config.realtime_priority,
              "SCHED_FIFO priority (1-99) of the threads that answer LineSets and exposure "
              "notices, so that background work does not delay an answer (needs CAP_SYS_NICE or "
              "ulimit -r); 0: time-shared");
  options.add("max_segments", config.max_segments, "LineSets with more segments are dropped");
  options.add("max_corners", config.max_corners, "LineSets with more corners are dropped");
  options.add("max_camera_side_px", config.max_camera_side_px,
              "LineSets whose camera image is wider or taller are dropped (pixels)");
  options.add("max_camera_megapixels", config.max_camera_megapixels,
              "LineSets whose camera image has more pixels are dropped (megapixels)");
  options.add("stats_file", config.stats_file, "JSON file the service counters are written to");
  options.add("stats_period_s", config.stats_period_s, "how often the stats file is rewritten");
  std::vector<double> sun_deg;
  options.addFixedSize("sun", sun_deg, 2,
                       "sun azimuth clockwise from grid north and elevation (deg): corners "
                       "between walls it lights alike are no edges (default: sun unknown)");
  options.addFlag("sun_from_clock", config.sun_from_clock,
                  "instead of --sun: the sun over the site at each LineSet's time (UTC), for "
                  "sunny days");
  options.add("ambient", config.ambient_fraction,
              "with a sun: fraction of the light in the shade, 0..1");
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  std::signal(SIGINT, requestStop);
  std::signal(SIGTERM, requestStop);
  lineloc::keepFreedMemoryResident();
  try {
    config.sunlight = lineloc::sunOption(sun_deg, config.ambient_fraction, "sun");
    const lineloc::BackboneCounters counters = lineloc::runBackbone(config, g_stop);
    std::cout << fmt::format(
        "lineloc-backbone: {} received, {} answered ({} with a pose, {} searched from a poor "
        "prediction, {} tracked with the hidden lines removed at exposure, {} exposure notices "
        "skipped as they came after their LineSet), {} dropped as invalid, {} map errors; {} "
        "frames answered busy as max_robots others were served, {} searches not queued\n",
        counters.received, counters.answered, counters.fixes_ok, counters.searches,
        counters.visibility_ahead, counters.notices_after_line_set, counters.dropped_invalid,
        counters.map_errors, counters.refused_robot_frames, counters.refused_searches);
    if (!config.learning_db.empty()) {
      const lineloc::LearningCounters& learnt = counters.learning;
      std::cout << fmt::format(
          "lineloc-backbone: learnt from {} frames ({} dropped as the learning fell behind): {} "
          "pieces written ({} failed, {} dropped), {} new candidates, {} lines seen again ({} "
          "confirmed), {} expected lines missed ({} retired)\n",
          learnt.frames, learnt.frames_dropped, learnt.pieces_written, learnt.write_failures,
          learnt.pieces_dropped, learnt.lines_added, learnt.lines_seen_again,
          learnt.lines_confirmed, learnt.lines_missed, learnt.lines_retired);
    }
    std::string stages;
    for (const lineloc::StagePercentiles& stage : lineloc::stagePercentiles(counters)) {
      stages += fmt::format(" {} {:.2f}/{:.2f}/{:.1f}", stage.stage, stage.median_ms, stage.p99_ms,
                            stage.max_ms);
    }
    std::cout << "lineloc-backbone: per LineSet, ms median/p99/max:" << stages << '\n';
    return 0;
  } catch (const std::exception& error) {
    spdlog::error("{}", error.what());
    return 1;
  }
}
