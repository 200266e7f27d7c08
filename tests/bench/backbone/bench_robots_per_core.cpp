// Robots served per backbone core at 30 Hz: N robots (1 to 8), each sending
// a tracked frame every 33.3 ms, their phases spread over the period,
// answered as lineloc-backbone answers them (one LineSetHandler, frames taken
// in the fair order of fair_frame_queue.h, a frame whose robot sent a newer
// one answered busy), with the whole process pinned to one CPU and its map
// read from PostGIS: the bundled Delft model in database lineloc_bench_delft
// of the deploy/pg.sh cluster (created and loaded on first run), or the
// server LINELOC_BENCH_DB names.
//
// Each robot drives the same simulated drive from its own place in it (robot
// r from frame r * frames / N), predicted from the truth moved by tracking's
// uncertainty (2 cm, 0.1 degree), and is handed over proven
// (tracking_handovers.h), as robots in steady state are: no proof search
// runs beside the frames.
//
// A frame's exposure -> fix is the robot's front end on it (measured here
// beforehand, one thread), the wait for and the answer on the backbone
// (measured here, in real time), and the DDS round trip (not included:
// bench_dds_round_trip measures it, p99 about 0.3 ms). N robots fit a core
// when the p99 of the first two is within the frame period and no frame is
// superseded. The table at the end gives each N; no library a user would
// pick serves robots' frames, so there is no baseline beside it.
//
// Run: build/bin/bench_robots_per_core (simulates and loads first, a minute).
#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <sched.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <map>
#include <random>
#include <thread>
#include <vector>

#include "backbone/map/database_tile_fetcher.h"
#include "backbone/service/fair_frame_queue.h"
#include "backbone/service/line_set_handler.h"
#include "common/time/clock.h"
#include "common/time/percentile.h"
#include "db/connection.h"
#include "db/loader/loader.h"
#include "db/migrations.h"
#include "tests/bench/backbone/delft_frames.h"
#include "tests/support/delft_drive.h"
#include "tests/support/test_database.h"

namespace lineloc {
namespace {

constexpr double kFramePeriodS = 1.0 / 30.0;
constexpr double kRunSeconds = 5.0;
constexpr double kTrackingPositionSigmaM = 0.02;
constexpr double kTrackingRotationSigmaRad = 0.1 * M_PI / 180.0;
constexpr char kSite[] = "delft";

std::string benchConninfo() {
  if (const char* conninfo = std::getenv("LINELOC_BENCH_DB")) {
    return conninfo;
  }
  const std::string cluster = test::clusterConninfo("55432", test::DatabaseRole::kOwner);
  db::Connection server(cluster);
  if (server.execParams("SELECT 1 FROM pg_database WHERE datname = $1", {"lineloc_bench_delft"})
          .rows() == 0) {
    server.exec("CREATE DATABASE lineloc_bench_delft");
  }
  // libpq takes the last value of a repeated keyword.
  return cluster + " dbname=lineloc_bench_delft";
}

// The Delft model in the benchmark's database, loaded when it is not.
const std::string& delftDatabase() {
  static const std::string conninfo = [] {
    const std::string conninfo = benchConninfo();
    db::Connection connection(conninfo);
    db::applyMigrations(connection, db::embeddedMigrations());
    db::LoadOptions options;
    options.site = kSite;
    options.site_origin = test::delftSiteOrigin();
    db::loadFile(test::delftCityModel().string(), options, &connection, nullptr);
    return conninfo;
  }();
  return conninfo;
}

const test::DelftFrames& delftFrames() {
  static const test::DelftFrames frames = test::simulateDelftFrames(12.0, 10.0);
  return frames;
}

// A handover that the robot's tracking is proven, for every robot.
std::optional<TrackingHandover> provenHandover(const std::string&) {
  return TrackingHandover{.stamp_ns = 1, .tracking = true, .agreeing_proofs = 1'000};
}

struct Outcome {
  std::vector<int64_t> backbone_ns;
  std::vector<int64_t> exposure_to_fix_ns;
  int superseded = 0;
  int ok = 0;
};

// Serves `robots` robots for kRunSeconds in real time on the calling thread.
Outcome serve(int robots) {
  const test::DelftFrames& drive = delftFrames();
  MapTileCache map([] { return makeDatabaseTileFetcher(delftDatabase(), kSite); }, 100.0, 256);
  PipelineOptions options;
  options.localizer.visibility.sunlight = drive.sunlight;
  LineSetHandler handler(map, MessageLimits{}, options, {nullptr, provenHandover});
  std::mt19937 random(7);
  const size_t frames = drive.frames.size();
  const int64_t period_ns = static_cast<int64_t>(kFramePeriodS * 1e9);
  const auto lineSet = [&](int robot, int64_t k, const char* name = "robot") {
    const test::DelftFrame& frame =
        drive.frames[(static_cast<size_t>(robot) * frames / robots + static_cast<size_t>(k)) %
                     frames];
    LineSetData line_set;
    line_set.robot_id = fmt::format("{}-{}", name, robot);
    line_set.sequence_number = static_cast<uint32_t>(k);
    line_set.stamp_ns = 1'000'000'000 + k * period_ns;
    line_set.camera = drive.calibration.camera;
    line_set.segments = frame.segments;
    line_set.corners = frame.corners;
    line_set.predicted_T_world_camera = test::predictedAround(frame.truth, kTrackingPositionSigmaM,
                                                              kTrackingRotationSigmaRad, random);
    return std::pair(line_set, frame.front_end_ns);
  };
  // Warm-up, off the clock, by robots of other names: the maps along every
  // robot's frames prepared.
  for (int robot = 0; robot < robots; ++robot) {
    for (int64_t k = 0; k < static_cast<int64_t>(kRunSeconds / kFramePeriodS); k += 10) {
      handler.answer(lineSet(robot, k, "warm-up").first, steadyClockNs());
      handler.waitForSearches();
    }
  }
  Outcome outcome;
  FairFrameQueue waiting;
  std::map<std::string, int64_t> front_end_ns;
  const int64_t start_ns = steadyClockNs() + period_ns;
  const int64_t frames_each = static_cast<int64_t>(kRunSeconds / kFramePeriodS);
  int64_t next = 0;  // the next arrival, over all robots in turn
  const int64_t arrivals = frames_each * robots;
  const auto arrivalNs = [&](int64_t arrival) {
    return start_ns + (arrival / robots) * period_ns + (arrival % robots) * period_ns / robots;
  };
  while (next < arrivals || !waiting.empty()) {
    while (next < arrivals && steadyClockNs() >= arrivalNs(next)) {
      auto [line_set, front_end] = lineSet(static_cast<int>(next % robots), next / robots);
      front_end_ns[line_set.robot_id + "#" + std::to_string(line_set.sequence_number)] = front_end;
      if (waiting.push(std::move(line_set), arrivalNs(next))) {
        ++outcome.superseded;
      }
      ++next;
    }
    const int64_t now_ns = steadyClockNs();
    if (const std::optional<FairFrameQueue::Taken> taken = waiting.pop(now_ns)) {
      const PoseFixData fix = handler.answer(taken->line_set, taken->taken_ns);
      const int64_t end_ns = steadyClockNs();
      waiting.charge(taken->line_set.robot_id, end_ns - now_ns, end_ns);
      const int64_t backbone_ns = end_ns - taken->taken_ns;
      outcome.backbone_ns.push_back(backbone_ns);
      outcome.exposure_to_fix_ns.push_back(
          backbone_ns + front_end_ns[taken->line_set.robot_id + "#" +
                                     std::to_string(taken->line_set.sequence_number)]);
      outcome.ok += fix.status == lineloc_msg_FIX_OK ? 1 : 0;
    } else if (next < arrivals) {
      std::this_thread::sleep_until(
          std::chrono::steady_clock::time_point(std::chrono::nanoseconds(arrivalNs(next))));
    }
  }
  return outcome;
}

struct Row {
  int robots = 0;
  double backbone_median_ms = 0.0;
  double backbone_p99_ms = 0.0;
  double exposure_to_fix_p99_ms = 0.0;
  int answered = 0;
  int ok = 0;
  int superseded = 0;
};

std::vector<Row>& table() {
  static std::vector<Row> rows;
  return rows;
}

void BM_RobotsPerCore(benchmark::State& state) {
  cpu_set_t one_cpu;
  CPU_ZERO(&one_cpu);
  CPU_SET(0, &one_cpu);
  // Every thread the handler starts from here on inherits the one CPU.
  if (sched_setaffinity(0, sizeof(one_cpu), &one_cpu) != 0) {
    state.SkipWithError("cannot pin the process to one CPU");
    return;
  }
  const int robots = static_cast<int>(state.range(0));
  Outcome outcome;
  for (auto _ : state) {
    outcome = serve(robots);
  }
  Row row{robots,
          toMilliseconds(percentile(outcome.backbone_ns, 50)),
          toMilliseconds(percentile(outcome.backbone_ns, 99)),
          toMilliseconds(percentile(outcome.exposure_to_fix_ns, 99)),
          static_cast<int>(outcome.backbone_ns.size()),
          outcome.ok,
          outcome.superseded};
  state.counters["backbone_p50_ms"] = row.backbone_median_ms;
  state.counters["backbone_p99_ms"] = row.backbone_p99_ms;
  state.counters["exposure_to_fix_p99_ms"] = row.exposure_to_fix_p99_ms;
  state.counters["superseded"] = row.superseded;
  table().push_back(row);
}

BENCHMARK(BM_RobotsPerCore)
    ->DenseRange(1, 8)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace
}  // namespace lineloc

int main(int argc, char** argv) {
  // The handler's warnings of answers slower than a frame would drown the table.
  spdlog::set_level(spdlog::level::err);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  using lineloc::table;
  fmt::print("\nrobots per core at 30 Hz (budget {:.1f} ms; DDS round trip not included)\n",
             lineloc::kFramePeriodS * 1e3);
  fmt::print(
      "| robots | backbone median ms | backbone p99 ms | exposure -> fix p99 ms | answered "
      "| OK | superseded | fits |\n|---|---|---|---|---|---|---|---|\n");
  int fitting = 0;
  for (const lineloc::Row& row : table()) {
    const bool fits =
        row.exposure_to_fix_p99_ms <= lineloc::kFramePeriodS * 1e3 && row.superseded == 0;
    fitting = fits && row.robots == fitting + 1 ? row.robots : fitting;
    fmt::print("| {} | {:.2f} | {:.2f} | {:.2f} | {} | {} | {} | {} |\n", row.robots,
               row.backbone_median_ms, row.backbone_p99_ms, row.exposure_to_fix_p99_ms,
               row.answered, row.ok, row.superseded, fits ? "yes" : "no");
  }
  fmt::print("robots served per core: {}\n", fitting);
  return 0;
}
