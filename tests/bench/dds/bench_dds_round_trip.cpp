// DDS round trip robot -> backbone -> robot for a LineSet of 300 segments,
// through a real lineloc-backbone process (which also queries PostGIS for the
// model lines near the predicted pose), beside Cyclone DDS's own ddsperf
// ping/pong with the same payload size on the same machine.
//
// Run: build/bin/bench_dds_round_trip  (starts the private PostGIS cluster on
// port 25435 with deploy/pg.sh, a backbone, and ddsperf from cyclonedds-tools).
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>

#include "common/messages/messages.h"
#include "common/messages/robot_partition.h"
#include "common/messages/topics.h"
#include "common/time/clock.h"
#include "common/time/percentile.h"
#include "tests/support/child_process.h"
#include "tests/support/test_database.h"
#include "tests/support/test_dds.h"

namespace lineloc {
namespace {

constexpr int kSegments = 300;
constexpr const char* kPgPort = "25435";
constexpr int kDdsperfSeconds = 5;
constexpr char kRobotId[] = "bench";

std::vector<double> g_round_trip_us;

LineSetData lineSetOf(int segments) {
  LineSetData data;
  data.robot_id = kRobotId;
  data.camera = {500, 500, 320, 240, 0, 640, 480};
  for (int i = 0; i < segments; ++i) {
    ImageSegment segment;
    segment.start = {static_cast<float>(i % 600), 10.0f};
    segment.end = {static_cast<float>(i % 600), 400.0f};
    segment.contrast = 40.0f;
    segment.polarity = 1;
    data.segments.push_back(segment);
  }
  data.predicted_T_world_camera.pose = makePose({5, -20, 1.5}, Eigen::Quaterniond::Identity());
  return data;
}

void BM_LineSetRoundTrip(benchmark::State& state) {
  setenv("LINELOC_PG_PORT", kPgPort, 1);
  setenv("LINELOC_TEST_PG_PORT", kPgPort, 1);
  if (std::system((std::string(LINELOC_SOURCE_DIR) + "/deploy/pg.sh start >/dev/null").c_str()) !=
      0) {
    state.SkipWithError("cannot start the PostGIS cluster");
    return;
  }
  test::TestDatabase database("bench_round_trip");
  test::insertCubeBuilding(database.conninfo(), 85000, 447000, 0, 0);
  const std::string log = (std::filesystem::temp_directory_path() / "bench_backbone.log").string();
  test::ChildProcess backbone(
      std::string(LINELOC_BIN_DIR) + "/lineloc-backbone",
      {"--domain-id", std::to_string(test::testDomainId()), "--dds-config", test::testDdsConfig(),
       "--db", database.conninfo(test::DatabaseRole::kReader), "--site", "test"},
      log);

  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant participant(domain);
  const std::string partition = robotPartition(kRobotId);
  dds::Reader<lineloc_msg_PoseFix> fixes(participant, dds::poseFixQos(8), partition);
  dds::Writer<lineloc_msg_LineSet> writer(participant, dds::Qos(8), partition);
  while (writer.matchedReaders() == 0 || fixes.matchedWriters() == 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  LineSetData line_set = lineSetOf(kSegments);
  uint32_t sequence = 0;
  g_round_trip_us.clear();
  for (auto _ : state) {
    line_set.sequence_number = ++sequence;
    line_set.stamp_ns = wallClockNs();
    const LineSetMessage message(line_set);
    const int64_t start_ns = steadyClockNs();
    writer.write(message.message());
    bool answered = false;
    while (!answered) {
      fixes.waitForData(1'000'000'000);
      fixes.takeEach(
          [&](const lineloc_msg_PoseFix& fix) { answered |= fix.sequence_number == sequence; });
    }
    const double seconds = (steadyClockNs() - start_ns) * 1e-9;
    state.SetIterationTime(seconds);
    g_round_trip_us.push_back(seconds * 1e6);
  }
  state.counters["segments"] = kSegments;
}
BENCHMARK(BM_LineSetRoundTrip)->UseManualTime()->Iterations(2000)->Unit(benchmark::kMicrosecond);

// ddsperf ping/pong with `payload_bytes`; returns its last statistics line.
std::string runDdsperf(size_t payload_bytes) {
  const auto folder = std::filesystem::temp_directory_path();
  const std::string domain = std::to_string(test::testDomainId() + 1);
  const std::string duration = std::to_string(kDdsperfSeconds);
  setenv("CYCLONEDDS_URI", ("file://" + test::testDdsConfig()).c_str(), 1);
  test::ChildProcess pong("/usr/bin/ddsperf", {"-D", duration, "-i", domain, "pong"},
                          (folder / "ddsperf_pong.log").string());
  test::ChildProcess ping(
      "/usr/bin/ddsperf",
      {"-D", duration, "-i", domain, "ping", "size", std::to_string(payload_bytes)},
      (folder / "ddsperf_ping.log").string());
  ping.wait((kDdsperfSeconds + 10) * 1000);
  std::ifstream stream(folder / "ddsperf_ping.log");
  std::string line, last;
  while (std::getline(stream, line)) {
    if (line.find(" mean ") != std::string::npos)
      last = line;
  }
  return last;
}

}  // namespace
}  // namespace lineloc

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  using lineloc::g_round_trip_us;
  if (g_round_trip_us.empty()) {
    return 1;
  }
  // The LineSet's payload: its segments plus the fixed part (pose, covariance, camera).
  const size_t payload =
      sizeof(lineloc_msg_LineSegment) * lineloc::kSegments + sizeof(lineloc_msg_LineSet);
  const std::string ddsperf = lineloc::runDdsperf(payload);
  const double median = lineloc::percentile(g_round_trip_us, 50);
  const double p99 = lineloc::percentile(g_round_trip_us, 99);
  std::printf(
      "\nlineloc LineSet (%d segments) robot -> backbone -> robot round trip, %zu samples:\n"
      "  median %.1f us, p99 %.1f us (includes the backbone's PostGIS query)\n",
      lineloc::kSegments, g_round_trip_us.size(), median, p99);
  std::printf("ddsperf ping/pong, payload %zu bytes, as ddsperf reports it:\n  %s\n", payload,
              ddsperf.c_str());
  const std::smatch match = [&] {
    std::smatch m;
    std::regex_search(ddsperf, m, std::regex(R"(50% ([0-9.]+)us .*99% ([0-9.]+)us)"));
    return m;
  }();
  if (match.size() == 3) {
    std::printf("ratio lineloc / ddsperf: median %.1fx, p99 %.1fx\n", median / std::stod(match[1]),
                p99 / std::stod(match[2]));
  }
  return 0;
}
