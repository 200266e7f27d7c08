// lineloc-backbone's service loop: subscribe to the LineSets of every robot,
// answer each with one PoseFix on the same DDS domain, until asked to stop.
#pragma once

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "backbone/service/line_set_handler.h"
#include "common/geometry/sunlight.h"

namespace lineloc {

struct BackboneConfig {
  int domain_id = 0;
  std::string dds_config;
  std::string db =
      "host=127.0.0.1 port=55432 user=lineloc_reader dbname=lineloc";  // read-only role
  std::string site = "delft";
  // The site's confirmed learnt lines (db/enrichment_store.h) are matched with
  // the model's, each weighted by its own uncertainty.
  bool use_learnt_lines = true;
  // The enricher role's connection string: lines are learnt from the frames
  // answered and stored in the site's enrichment (online_learning.h); empty:
  // none are.
  std::string learning_db;
  // This backbone's name among the backbones sharing the domain's robots
  // (backbone_peers.h), [A-Za-z0-9][A-Za-z0-9_.-]*; empty: <hostname>-<pid>.
  // Each robot is served by one backbone alive, chosen by name
  // (robot_assignment.h); a backbone silent for backbone_lease_s is no longer.
  std::string backbone_name;
  double backbone_lease_s = 1.0;
  double query_radius_m = 150.0;
  double tile_size_m = 100.0;
  int max_cached_tiles = 4096;
  double prefetch_lookahead_s = 3.0;
  // A robot not heard from for this long is forgotten; at most max_robots are
  // served at once and max_queued_searches searches wait in all; frames
  // beyond are answered FIX_BUSY (line_set_handler.h).
  double forget_robot_after_s = 30.0;
  int max_robots = 64;
  int max_queued_searches = 8;
  // Threads answering LineSets at once, each robot's one at a time
  // (frame_workers.h); 0: one per core the process may run on.
  int answer_threads = 0;
  // SCHED_FIFO priority (1-99) of the threads a frame's answer waits on, the
  // LineSets' and the exposure notices' (thread_priority.h); 0: time-shared.
  // Below a robot's front end sharing the machine, above the searches and the
  // map preparation; Cyclone's receive thread, which hands them their
  // samples, may sit between the two (deploy/cyclonedds-realtime.xml). A
  // refusal is logged and they run time-shared.
  int realtime_priority = 0;
  // LineSets beyond these limits are dropped (message_validator.h).
  int max_segments = 2048;
  int max_corners = 2048;
  int max_camera_side_px = 8192;
  double max_camera_megapixels = 32.0;
  // Written on exit (and every stats_period_s): counters as JSON; empty: none.
  std::string stats_file;
  double stats_period_s = 1.0;
  // The sun over the site, when known (see VisibilityOptions::sunlight).
  std::optional<Sunlight> sunlight;
  // Instead: the sun that stands over the site at each LineSet's stamp (UTC),
  // common/geodesy/site_sun.h, with this ambient fraction; for sunny days.
  bool sun_from_clock = false;
  double ambient_fraction = 0.35;
};

// Serves until `stop` is true; returns the final counters. Starts without
// its database, looking the site up every few seconds until the database
// answers (and taking the sun over it then, with sun_from_clock); throws
// std::runtime_error, naming the site, once the database says it holds no
// such site. Stopping drops the queued searches and cancels the one running
// (line_set_handler.h).
BackboneCounters runBackbone(const BackboneConfig& config, const std::atomic<bool>& stop);

// Median, 99th percentile and maximum (ms) of each stage over the counters'
// recent answers: the maximum shows which stage a single stall was in.
struct StagePercentiles {
  std::string stage;
  double median_ms = 0.0;
  double p99_ms = 0.0;
  double max_ms = 0.0;
};
std::vector<StagePercentiles> stagePercentiles(const BackboneCounters& counters);

// Writes the counters and stage percentiles as a JSON object to `path`
// (atomically, by rename).
void writeCountersJson(const BackboneCounters& counters, const std::string& path);

}  // namespace lineloc
