#include "backbone/service/backbone_service.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "backbone/map/database_tile_fetcher.h"
#include "backbone/service/backbone_peers.h"
#include "backbone/service/frame_workers.h"
#include "backbone/service/pose_fix_publisher.h"
#include "backbone/service/site_lookup.h"
#include "backbone/service/tracking_handovers.h"
#include "common/logging/rate_limited_log.h"
#include "common/messages/robot_partition.h"
#include "common/messages/topics.h"
#include "common/parallel/parallel_for.h"
#include "common/parallel/periodic_task.h"
#include "common/parallel/realtime_thread.h"
#include "common/time/clock.h"
#include "common/time/percentile.h"
#include "db/site.h"

namespace lineloc {
namespace {

constexpr int64_t kWaitNs = 100'000'000;
// How often the backbones alive are looked at: a small part of their 1 s
// liveliness lease, not at every frame.
constexpr int64_t kPeersRefreshNs = 20'000'000;
constexpr std::chrono::seconds kSiteRetryPeriod(2);

// The configured name, or <hostname>-<pid>.
std::string backboneName(const BackboneConfig& config) {
  if (!config.backbone_name.empty()) {
    return config.backbone_name;
  }
  std::array<char, 256> host{};
  gethostname(host.data(), host.size() - 1);
  std::string name = fmt::format("{}-{}", host.data(), getpid());
  std::replace_if(
      name.begin(), name.end(),
      [](char c) { return !std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.'; },
      '-');
  return name.substr(0, lineloc_msg_BACKBONE_NAME_MAX_LENGTH);
}

std::string notInItsPartition(const lineloc_msg_LineSet& message) {
  return fmt::format("robot_id '{}' written outside partition '{}'", std::string(message.robot_id),
                     robotPartition(message.robot_id));
}

// Looks the configured site up (site_lookup.h) at once and, while the
// database cannot be reached, again every kSiteRetryPeriod: the backbone
// starts and serves without its database. Found, the site gives the handler
// the sun over it when asked for (--sun-from-clock); missing, it is the
// refusal the backbone stops serving with.
class SiteWatch {
 public:
  SiteWatch(const BackboneConfig& config, LineSetHandler& handler)
      : config_(config), handler_(handler), unreachable_log_("site lookups failed", 1, 60.0) {
    if (!attempt()) {
      retries_.emplace(kSiteRetryPeriod, [this] { attempt(); });
    }
  }

  bool refused() const { return refused_; }
  std::optional<std::string> refusal() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return refusal_;
  }

 private:
  // Looks the site up unless the database has answered; true once it has.
  bool attempt() {
    if (answered_) {
      return true;
    }
    const SiteLookup lookup = lookUpSite(config_.db, config_.site);
    if (lookup.outcome == SiteLookup::Outcome::kUnreachable) {
      unreachable_log_.log(
          fmt::format("{}; looking again every {} s", lookup.error, kSiteRetryPeriod.count()));
      return false;
    }
    answered_ = true;
    if (lookup.outcome == SiteLookup::Outcome::kMissing) {
      refuse(lookup.error);
      return true;
    }
    spdlog::info("site '{}' found in the database", config_.site);
    if (config_.sun_from_clock) {
      try {
        takeSunOver(*lookup.site);
      } catch (const std::exception& error) {
        refuse(fmt::format("the sun over site '{}': {}", config_.site, error.what()));
      }
    }
    return true;
  }

  void takeSunOver(const db::Site& site) {
    const SiteSun sun(SiteProjection(fmt::format("EPSG:{}", site.srid), site.origin),
                      config_.ambient_fraction);
    handler_.takeSunFromClock(sun);
    const GeodeticPosition& place = sun.place();
    spdlog::info("the sun by the clock over site '{}' at latitude {:.4f}, longitude {:.4f}",
                 config_.site, place.latitude_deg, place.longitude_deg);
  }

  void refuse(const std::string& why) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      refusal_ = why;
    }
    refused_ = true;
  }

  const BackboneConfig& config_;
  LineSetHandler& handler_;
  RateLimitedLog unreachable_log_;
  std::atomic<bool> answered_{false};
  std::atomic<bool> refused_{false};
  mutable std::mutex mutex_;
  std::optional<std::string> refusal_;
  // Last, so that it is destroyed first: its task uses the members above.
  std::optional<PeriodicTask> retries_;
};

// Writes config.stats_file now, which fails the start when it cannot be
// written, then every stats_period_s beside the serving loop
// (periodic_task.h); none without a stats file. A later failed write is
// logged and tried again a period later: serving goes on.
std::optional<PeriodicTask> periodicStatsFile(const BackboneConfig& config,
                                              const LineSetHandler& handler) {
  if (config.stats_file.empty()) {
    return std::nullopt;
  }
  writeCountersJson(handler.counters(), config.stats_file);
  const std::chrono::nanoseconds period(static_cast<int64_t>(config.stats_period_s * 1e9));
  return std::optional<PeriodicTask>(std::in_place, period, [&config, &handler] {
    try {
      writeCountersJson(handler.counters(), config.stats_file);
    } catch (const std::exception& error) {
      spdlog::warn("stats file not written: {}", error.what());
    }
  });
}

}  // namespace

std::vector<StagePercentiles> stagePercentiles(const BackboneCounters& counters) {
  const std::pair<const char*, int64_t StageTimingsNs::*> stages[] = {
      {"map", &StageTimingsNs::map},
      {"visibility", &StageTimingsNs::visibility},
      {"matching", &StageTimingsNs::matching},
      {"pose", &StageTimingsNs::pose},
      {"total", &StageTimingsNs::total}};
  std::vector<StagePercentiles> result;
  for (const auto& [stage, member] : stages) {
    std::vector<int64_t> times_ns;
    times_ns.reserve(counters.recent_timings.size());
    for (const StageTimingsNs& timings : counters.recent_timings) {
      times_ns.push_back(timings.*member);
    }
    result.push_back({stage, toMilliseconds(percentile(times_ns, 50)),
                      toMilliseconds(percentile(times_ns, 99)),
                      toMilliseconds(percentile(times_ns, 100))});
  }
  return result;
}

void writeCountersJson(const BackboneCounters& counters, const std::string& path) {
  nlohmann::json stage_ms;
  for (const StagePercentiles& stage : stagePercentiles(counters)) {
    stage_ms[stage.stage] = {
        {"median", stage.median_ms}, {"p99", stage.p99_ms}, {"max", stage.max_ms}};
  }
  const LearningCounters& learnt = counters.learning;
  const nlohmann::json learning = {{"frames", learnt.frames},
                                   {"frames_dropped", learnt.frames_dropped},
                                   {"pieces_written", learnt.pieces_written},
                                   {"pieces_dropped", learnt.pieces_dropped},
                                   {"write_failures", learnt.write_failures},
                                   {"lines_added", learnt.lines_added},
                                   {"lines_seen_again", learnt.lines_seen_again},
                                   {"lines_confirmed", learnt.lines_confirmed},
                                   {"lines_missed", learnt.lines_missed},
                                   {"lines_retired", learnt.lines_retired}};
  const nlohmann::json json = {{"received", counters.received},
                               {"answered", counters.answered},
                               {"fixes_ok", counters.fixes_ok},
                               {"dropped_invalid", counters.dropped_invalid},
                               {"map_errors", counters.map_errors},
                               {"searches", counters.searches},
                               {"visibility_ahead", counters.visibility_ahead},
                               {"notices_after_line_set", counters.notices_after_line_set},
                               {"robots", counters.robots},
                               {"robots_forgotten", counters.robots_forgotten},
                               {"refused_robot_frames", counters.refused_robot_frames},
                               {"refused_searches", counters.refused_searches},
                               {"superseded_frames", counters.superseded_frames},
                               {"late_frames", counters.late_frames},
                               {"backbones", counters.backbones},
                               {"frames_served_elsewhere", counters.frames_served_elsewhere},
                               {"learning", learning},
                               {"last_drop_reason", counters.last_drop_reason},
                               {"stage_ms", stage_ms}};
  const std::string temporary = path + ".tmp";
  {
    std::ofstream stream(temporary);
    if (!stream) {
      throw std::runtime_error(fmt::format("cannot write stats file '{}'", temporary));
    }
    stream << json.dump(2) << '\n';
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    throw std::runtime_error(fmt::format("cannot rename '{}' to '{}'", temporary, path));
  }
}

BackboneCounters runBackbone(const BackboneConfig& config, const std::atomic<bool>& stop) {
  if (config.max_segments <= 0 || config.max_corners < 0 || config.max_camera_side_px <= 0 ||
      !(config.max_camera_megapixels > 0.0) || config.query_radius_m <= 0.0 ||
      config.tile_size_m <= 0.0 || config.max_cached_tiles <= 0 || !(config.stats_period_s > 0.0) ||
      !(config.forget_robot_after_s > 0.0) || config.max_robots <= 0 ||
      config.max_queued_searches <= 0) {
    throw std::runtime_error(
        "max_segments, max_camera_side_px, max_camera_megapixels, query_radius_m, tile_size_m, "
        "max_cached_tiles, stats_period_s, forget_robot_after_s, max_robots and "
        "max_queued_searches must be positive");
  }
  if (config.answer_threads < 0) {
    throw std::runtime_error("answer_threads must not be negative (0: one per core)");
  }
  requireRealtimePriority(config.realtime_priority);
  if (config.sun_from_clock && config.sunlight) {
    throw std::runtime_error(
        "give the sun's azimuth and elevation or take it from the clock, not both");
  }
  MessageLimits limits;
  limits.max_segments = static_cast<uint32_t>(config.max_segments);
  limits.max_corners = static_cast<uint32_t>(config.max_corners);
  limits.max_camera_side_px = static_cast<uint32_t>(config.max_camera_side_px);
  limits.max_camera_megapixels = config.max_camera_megapixels;
  MapTileCache map(
      [&config] {
        return makeDatabaseTileFetcher(config.db, config.site, config.use_learnt_lines);
      },
      config.tile_size_m, static_cast<size_t>(config.max_cached_tiles));
  PipelineOptions pipeline;
  pipeline.query_radius_m = config.query_radius_m;
  pipeline.prefetch_lookahead_s = config.prefetch_lookahead_s;
  pipeline.forget_robot_after_s = config.forget_robot_after_s;
  pipeline.max_robots = config.max_robots;
  pipeline.max_queued_searches = config.max_queued_searches;
  pipeline.learning.db = config.learning_db;
  pipeline.learning.site = config.site;
  pipeline.localizer.visibility.sunlight = config.sunlight;
  dds::Domain domain(config.domain_id, config.dds_config);
  dds::logSecurity(domain);
  dds::Participant participant(domain);
  dds::Reader<lineloc_msg_LineSet> reader(participant, dds::Qos(dds::kHistoryDepth),
                                          kEveryRobotPartition);
  dds::Reader<lineloc_msg_LineSet, dds::ExposureTopic> exposures(
      participant, dds::Qos(dds::kHistoryDepth), kEveryRobotPartition);
  PoseFixPublisher fixes(participant, static_cast<int64_t>(config.forget_robot_after_s * 1e9));
  BackbonePeers peers(participant, backboneName(config),
                      static_cast<int64_t>(config.backbone_lease_s * 1e9));
  TrackingHandovers handovers(participant, peers.name(),
                              static_cast<int64_t>(config.forget_robot_after_s * 1e9));
  LineSetHandler handler(map, limits, pipeline, handovers.channel());
  spdlog::info("backbone '{}': serving its share of the robots with the backbones alive",
               peers.name());
  const SiteWatch site(config, handler);
  const auto serving = [&] { return !stop && !site.refused(); };
  if (serving()) {
    spdlog::info("serving LineSets on DDS domain {} for site '{}'", config.domain_id, config.site);
  }
  {
    const std::optional<PeriodicTask> stats_writer = periodicStatsFile(config, handler);
    // Exposure notices on a thread of their own: a robot's frame is exposed
    // while the backbone may still answer another robot's LineSet.
    const std::jthread exposure_thread([&] {
      runThreadRealtimeLogged(config.realtime_priority, "exposure notices' thread");
      while (serving()) {
        if (exposures.waitForData(kWaitNs)) {
          exposures.takeEach([&](const lineloc_msg_LineSet& message, const dds::SampleInfo& info) {
            if (!speaksFor(exposures.writerPartitions(info.publication_handle), message.robot_id)) {
              handler.countDrop("exposure notice", message.sequence_number,
                                notInItsPartition(message));
            } else if (peers.serves(message.robot_id)) {
              handler.handleExposure(message);
            }
          });
        }
      }
    });
    // After every background thread has started: they stay time-shared.
    runThreadRealtimeLogged(config.realtime_priority, "LineSets' thread");
    // Every LineSet that has come is taken at once, and the fairest waiting
    // is answered by the next thread free (frame_workers.h).
    FrameWorkers workers(
        config.answer_threads > 0 ? config.answer_threads : hardwareThreads(),
        {.answer = [&](const LineSetData& line_set,
                       int64_t taken_ns) { return handler.answer(line_set, taken_ns); },
         .busy = [&](const LineSetData& line_set, int64_t taken_ns,
                     FrameRefusal why) { return handler.answerBusy(line_set, taken_ns, why); },
         .publish =
             [&](const PoseFixData& fix) {
               fixes.publish(fix, steadyClockNs());
               handovers.writeQueued();
             }},
        [&config] { runThreadRealtimeLogged(config.realtime_priority, "LineSets' threads"); });
    uint32_t robot_writers_seen = 0;
    int64_t peers_refreshed_ns = 0;
    while (serving()) {
      const bool data = reader.waitForData(kWaitNs);
      if (steadyClockNs() - peers_refreshed_ns >= kPeersRefreshNs) {
        handler.countBackbones(peers.refresh().size());
        peers_refreshed_ns = steadyClockNs();
      }
      const uint32_t robot_writers = reader.matchedWriters();
      if (!data || robot_writers != robot_writers_seen) {
        robot_writers_seen = robot_writers;
        fixes.follow(reader.matchedWritersPartitions(), steadyClockNs());
      }
      if (!data) {
        handler.forgetSilentRobotsWhenDue(steadyClockNs());
        handler.flushLogs(steadyClockNs());
        continue;
      }
      reader.takeEach([&](const lineloc_msg_LineSet& message, const dds::SampleInfo& info) {
        if (!speaksFor(reader.writerPartitions(info.publication_handle), message.robot_id)) {
          handler.countDrop("LineSet", message.sequence_number, notInItsPartition(message));
        } else if (!peers.serves(message.robot_id)) {
          handler.leaveToAnotherBackbone(message.robot_id);
        } else if (std::optional<LineSetData> line_set = handler.accept(message)) {
          workers.take(std::move(*line_set), steadyClockNs());
        }
      });
    }
  }
  handler.stopLearning();
  if (!config.stats_file.empty()) {
    writeCountersJson(handler.counters(), config.stats_file);
  }
  if (const std::optional<std::string> refusal = site.refusal()) {
    throw std::runtime_error(*refusal + ": not serving it");
  }
  return handler.counters();
}

}  // namespace lineloc
