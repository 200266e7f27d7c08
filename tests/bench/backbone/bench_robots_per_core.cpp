// Robots served by one backbone at 30 Hz: N robots (1 to 8 on one core, 4 to
// 16 on two), each sending a tracked frame every 33.3 ms, their phases spread
// over the period, answered as lineloc-backbone answers them (one
// LineSetHandler; a FrameWorkers thread per core answering in the fair order
// of fair_frame_queue.h, a frame superseded or late answered busy), with the
// whole process pinned to that many CPUs and its map read from PostGIS: the
// bundled Delft model in database lineloc_bench_delft of the deploy/pg.sh
// cluster (created and loaded on first run), or the server LINELOC_BENCH_DB
// names.
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
// bench_dds_round_trip measures it, p99 about 0.3 ms). N robots fit when the
// p99 of the first two is within the frame period and no frame is answered
// busy. The table at the end gives each N; no library a user would
// pick serves robots' frames, so there is no baseline beside it.
//
// Run: build/bin/bench_robots_per_core (simulates and loads first, a minute).
#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <sched.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <random>
#include <thread>
#include <vector>

#include "backbone/map/database_tile_fetcher.h"
#include "backbone/service/frame_workers.h"
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
  int ok = 0;
  // Answered FIX_BUSY: superseded by the robot's next frame, or late.
  int superseded = 0;
  int late = 0;
};

// Serves `robots` robots for kRunSeconds in real time: the calling thread
// takes their frames as they come, `threads` FrameWorkers threads answer them.
Outcome serve(int robots, int threads) {
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
  std::mutex mutex;
  // Each frame's arrival and front-end time, by robot and sequence number.
  std::map<std::pair<std::string, uint32_t>, std::pair<int64_t, int64_t>> sent;
  const auto publish = [&](const PoseFixData& fix) {
    const int64_t answered_ns = steadyClockNs();
    const std::lock_guard<std::mutex> lock(mutex);
    if (fix.status == lineloc_msg_FIX_BUSY) {
      return;
    }
    const auto [arrival_ns, front_end_ns] = sent.at({fix.robot_id, fix.sequence_number});
    outcome.backbone_ns.push_back(answered_ns - arrival_ns);
    outcome.exposure_to_fix_ns.push_back(answered_ns - arrival_ns + front_end_ns);
    outcome.ok += fix.status == lineloc_msg_FIX_OK ? 1 : 0;
  };
  FrameWorkers workers(
      threads,
      {.answer = [&](const LineSetData& line_set,
                     int64_t taken_ns) { return handler.answer(line_set, taken_ns); },
       .busy = [&](const LineSetData& line_set, int64_t taken_ns,
                   FrameRefusal why) { return handler.answerBusy(line_set, taken_ns, why); },
       .publish = publish});
  const int64_t start_ns = steadyClockNs() + period_ns;
  const int64_t arrivals = static_cast<int64_t>(kRunSeconds / kFramePeriodS) * robots;
  for (int64_t arrival = 0; arrival < arrivals; ++arrival) {
    const int64_t arrival_ns =
        start_ns + (arrival / robots) * period_ns + (arrival % robots) * period_ns / robots;
    auto [line_set, front_end_ns] = lineSet(static_cast<int>(arrival % robots), arrival / robots);
    std::this_thread::sleep_until(
        std::chrono::steady_clock::time_point(std::chrono::nanoseconds(arrival_ns)));
    {
      const std::lock_guard<std::mutex> lock(mutex);
      sent[{line_set.robot_id, line_set.sequence_number}] = {arrival_ns, front_end_ns};
    }
    workers.take(std::move(line_set), arrival_ns);
  }
  workers.waitUntilIdle();
  const BackboneCounters counters = handler.counters();
  const std::lock_guard<std::mutex> lock(mutex);
  outcome.superseded = static_cast<int>(counters.superseded_frames);
  outcome.late = static_cast<int>(counters.late_frames);
  return outcome;
}

struct Row {
  int cores = 0;
  int robots = 0;
  double backbone_median_ms = 0.0;
  double backbone_p99_ms = 0.0;
  double exposure_to_fix_p99_ms = 0.0;
  int answered = 0;
  int ok = 0;
  int superseded = 0;
  int late = 0;
};

std::vector<Row>& table() {
  static std::vector<Row> rows;
  return rows;
}

// The CPUs the process may run on when it started.
const cpu_set_t& startingCpus() {
  static const cpu_set_t cpus = [] {
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    sched_getaffinity(0, sizeof(allowed), &allowed);
    return allowed;
  }();
  return cpus;
}

// Pins the process to the first `cores` of startingCpus(); false when it
// has fewer.
bool pinTo(int cores) {
  cpu_set_t pinned;
  CPU_ZERO(&pinned);
  int taken = 0;
  for (int cpu = 0; cpu < CPU_SETSIZE && taken < cores; ++cpu) {
    if (CPU_ISSET(cpu, &startingCpus())) {
      CPU_SET(cpu, &pinned);
      ++taken;
    }
  }
  return taken == cores && sched_setaffinity(0, sizeof(pinned), &pinned) == 0;
}

// range(0) robots on range(1) cores, as many FrameWorkers threads.
void BM_RobotsPerCore(benchmark::State& state) {
  const int robots = static_cast<int>(state.range(0));
  const int cores = static_cast<int>(state.range(1));
  // Every thread the handler starts from here on inherits the CPUs.
  if (!pinTo(cores)) {
    state.SkipWithError("cannot pin the process to that many CPUs");
    return;
  }
  Outcome outcome;
  for (auto _ : state) {
    outcome = serve(robots, cores);
  }
  Row row{cores,
          robots,
          toMilliseconds(percentile(outcome.backbone_ns, 50)),
          toMilliseconds(percentile(outcome.backbone_ns, 99)),
          toMilliseconds(percentile(outcome.exposure_to_fix_ns, 99)),
          static_cast<int>(outcome.backbone_ns.size()),
          outcome.ok,
          outcome.superseded,
          outcome.late};
  state.counters["backbone_p50_ms"] = row.backbone_median_ms;
  state.counters["backbone_p99_ms"] = row.backbone_p99_ms;
  state.counters["exposure_to_fix_p99_ms"] = row.exposure_to_fix_p99_ms;
  state.counters["superseded"] = row.superseded;
  state.counters["late"] = row.late;
  table().push_back(row);
}

void robotsAndCores(benchmark::internal::Benchmark* benchmark) {
  for (int robots = 1; robots <= 8; ++robots) {
    benchmark->Args({robots, 1});
  }
  for (int robots = 4; robots <= 16; robots += 2) {
    benchmark->Args({robots, 2});
  }
}

BENCHMARK(BM_RobotsPerCore)
    ->Apply(robotsAndCores)
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
  fmt::print("\nrobots per backbone at 30 Hz (budget {:.1f} ms; DDS round trip not included)\n",
             lineloc::kFramePeriodS * 1e3);
  fmt::print(
      "| cores | robots | backbone median ms | backbone p99 ms | exposure -> fix p99 ms | "
      "answered | OK | superseded | late | fits |\n|---|---|---|---|---|---|---|---|---|---|\n");
  // Per core count: the most robots such that they and every smaller count
  // measured fit.
  std::map<int, int> fitting;
  std::map<int, bool> all_fit;
  for (const lineloc::Row& row : table()) {
    const bool fits = row.exposure_to_fix_p99_ms <= lineloc::kFramePeriodS * 1e3 &&
                      row.superseded == 0 && row.late == 0;
    if (!all_fit.contains(row.cores)) {
      all_fit[row.cores] = true;
    }
    all_fit[row.cores] = all_fit[row.cores] && fits;
    if (all_fit[row.cores]) {
      fitting[row.cores] = row.robots;
    }
    fmt::print("| {} | {} | {:.2f} | {:.2f} | {:.2f} | {} | {} | {} | {} | {} |\n", row.cores,
               row.robots, row.backbone_median_ms, row.backbone_p99_ms, row.exposure_to_fix_p99_ms,
               row.answered, row.ok, row.superseded, row.late, fits ? "yes" : "no");
  }
  for (const auto& [cores, robots] : fitting) {
    fmt::print("robots served on {} core(s): {} ({:.1f} per core)\n", cores, robots,
               static_cast<double>(robots) / cores);
  }
  return 0;
}
