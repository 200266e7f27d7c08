// The robot <-> backbone loop with real processes: lineloc-backbone and
// lineloc-robot as separate programs, a real PostGIS database, real DDS
// participants on loopback. The test process is a third DDS participant that
// listens to every LineSet and PoseFix and injects malformed LineSets.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <random>
#include <regex>
#include <set>
#include <thread>
#include <vector>

#include "backbone/service/robot_assignment.h"
#include "common/messages/messages.h"
#include "common/messages/robot_partition.h"
#include "common/messages/topics.h"
#include "common/time/clock.h"
#include "common/trajectory/tum_trajectory.h"
#include "robot/inertial/inertial_navigator_config.h"
#include "robot/ros2/ros2_topics.h"
#include "robot/ros2/ros2_wire.h"
#include "tests/support/child_process.h"
#include "tests/support/foxglove_cdr.h"
#include "tests/support/serialized_samples.h"
#include "tests/support/test_database.h"
#include "tests/support/test_dds.h"

namespace fs = std::filesystem;

namespace lineloc {
namespace {

constexpr int kFrames = 12;
constexpr int kBackboneMaxSegments = 1000;
constexpr int kTimeoutMs = 30'000;
constexpr int64_t kFirstFrameNs = 1'700'000'000'000'000'000;
// The backbone's peak resident memory under the flood test's 16 robot ids:
// its working set (under 50 MiB), plus at most kHistoryDepth LineSets of
// 4,096 segments (48 bytes each, 192 KiB a LineSet) per flooding robot in
// DDS's reader, 16 x 32 x 192 KiB = 96 MiB, plus one waiting LineSet per
// robot in the fair queue, with room for the allocator's slack.
constexpr int64_t kMaxFloodedBackboneKiB = 256 * 1024;

// Synthetic façade frames: a building outline with a grid of windows, shifted
// a little from frame to frame, so the extractor finds segments in each.
void writeFacadeFrames(const fs::path& folder, int count) {
  fs::create_directories(folder);
  for (int i = 0; i < count; ++i) {
    cv::Mat image(480, 640, CV_8UC1, cv::Scalar(200));
    const int shift = 3 * i;
    cv::rectangle(image, {100 + shift, 80}, {540 + shift, 470}, cv::Scalar(90), cv::FILLED);
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 4; ++col) {
        const cv::Point corner(130 + shift + col * 100, 110 + row * 110);
        cv::rectangle(image, corner, corner + cv::Point(60, 70), cv::Scalar(30), cv::FILLED);
      }
    }
    cv::imwrite((folder / cv::format("frame%03d.png", i)).string(), image);
  }
}

// The robot numbers its frames 0, 1, ... in image order.
std::set<uint32_t> frameIndices() {
  std::set<uint32_t> indices;
  for (uint32_t i = 0; i < static_cast<uint32_t>(kFrames); ++i) {
    indices.insert(i);
  }
  return indices;
}

void writeCalibration(const fs::path& path) {
  cv::FileStorage storage(path.string(), cv::FileStorage::WRITE);
  storage << "image_width" << 640 << "image_height" << 480;
  storage << "camera_matrix" << (cv::Mat_<double>(3, 3) << 500, 0, 320, 0, 500, 240, 0, 0, 1);
  storage << "distortion_coefficients" << cv::Mat::zeros(5, 1, CV_64F);
}

// A timed camera folder of three frames 50 ms apart, as a dataset holds it:
// `dataset`/cam0.
void writeTimedCameraFolder(const fs::path& dataset) {
  const fs::path camera = dataset / "cam0";
  fs::create_directories(camera / "data");
  std::ofstream csv(camera / "data.csv");
  csv << "#timestamp [ns],filename\n";
  for (int i = 0; i < 3; ++i) {
    const std::string name = cv::format("frame%03d.png", i);
    fs::copy_file(dataset.parent_path() / "images" / name, camera / "data" / name);
    csv << kFirstFrameNs + i * 50'000'000LL << ',' << name << '\n';
  }
}

// An IMU standing level from 3 s before the first frame (the alignment
// window is 2 s) to 300 ms after it, at 200 Hz: `dataset`/imu0.
void writeStandingImu(const fs::path& dataset) {
  fs::create_directories(dataset / "imu0");
  std::ofstream csv(dataset / "imu0" / "data.csv");
  csv << "#timestamp [ns],w_x,w_y,w_z,a_x,a_y,a_z\n";
  for (int64_t stamp_ns = kFirstFrameNs - 3'000'000'000; stamp_ns <= kFirstFrameNs + 300'000'000;
       stamp_ns += 5'000'000) {
    csv << stamp_ns << ",0,0,0,0,0,9.80665\n";
  }
}

// The robot whose messages the observer writes.
constexpr char kProbeRobot[] = "probe";

// The test's own DDS participant: sees every LineSet and PoseFix on the
// domain, and writes LineSets in the partition of kProbeRobot.
class Observer {
 public:
  explicit Observer(const std::string& dds_config = test::testDdsConfig())
      : domain_(test::testDomainId(), dds_config),
        participant_(domain_),
        line_sets_(participant_, dds::Qos(256), kEveryRobotPartition),
        fixes_(participant_, dds::poseFixQos(256), kEveryRobotPartition),
        writer_(participant_, dds::Qos(dds::kHistoryDepth), robotPartition(kProbeRobot)),
        exposure_writer_(participant_, dds::Qos(dds::kHistoryDepth), robotPartition(kProbeRobot)) {}

  void poll() {
    fixes_.waitForData(5'000'000);
    fixes_.takeEach([this](const lineloc_msg_PoseFix& m) { fixes.push_back(fromMessage(m)); });
    line_sets_.takeEach([this](const lineloc_msg_LineSet& m) {
      sent_stamps[m.robot_id][m.sequence_number] = m.stamp_ns;
    });
  }

  template <typename Predicate>
  bool pollUntil(Predicate&& done, int timeout_ms = kTimeoutMs) {
    const int64_t deadline = steadyClockNs() + int64_t{timeout_ms} * 1'000'000;
    while (!done()) {
      if (steadyClockNs() > deadline) {
        return false;
      }
      poll();
    }
    return true;
  }

  const dds::Participant& participant() const { return participant_; }
  dds::Writer<lineloc_msg_LineSet>& writer() { return writer_; }
  dds::Writer<lineloc_msg_LineSet, dds::ExposureTopic>& exposureWriter() {
    return exposure_writer_;
  }
  // The observer's own LineSet reader is one of the writer's matched readers.
  bool backboneListening() const {
    return writer_.matchedReaders() >= 2 && exposure_writer_.matchedReaders() >= 1;
  }
  size_t fixesFor(const std::string& robot_id) const {
    return std::count_if(fixes.begin(), fixes.end(),
                         [&](const PoseFixData& f) { return f.robot_id == robot_id; });
  }

  std::vector<PoseFixData> fixes;
  std::map<std::string, std::map<uint32_t, int64_t>> sent_stamps;

 private:
  dds::Domain domain_;
  dds::Participant participant_;
  dds::Reader<lineloc_msg_LineSet> line_sets_;
  dds::Reader<lineloc_msg_PoseFix> fixes_;
  dds::Writer<lineloc_msg_LineSet> writer_;
  dds::Writer<lineloc_msg_LineSet, dds::ExposureTopic> exposure_writer_;
};

// The count in the robot's summary line "... N fixes received ...".
int fixesReceived(const std::string& robot_log) {
  std::smatch match;
  if (!std::regex_search(robot_log, match, std::regex(R"(([0-9]+) fixes received)"))) {
    return -1;
  }
  return std::stoi(match[1]);
}

// The medians (ms) of the robot's exposure -> fix split: front end, to the
// backbone, backbone, back; empty when its log holds no such line.
std::vector<double> latencyStageMedians(const std::string& robot_log) {
  std::smatch match;
  const std::regex stages(
      R"(front end ([-0-9.]+)/.*, to the backbone ([-0-9.]+)/.*, backbone ([-0-9.]+)/.*, )"
      R"(back ([-0-9.]+)/)");
  if (!std::regex_search(robot_log, match, stages)) {
    return {};
  }
  return {std::stod(match[1]), std::stod(match[2]), std::stod(match[3]), std::stod(match[4])};
}

// Whether the backbone's log says its `thread` runs under SCHED_FIFO at
// `priority`, or that the machine refused it that.
bool askedForRealtimePriority(const std::string& backbone_log, const std::string& thread,
                              int priority) {
  const std::string granted =
      fmt::format("the {} runs under SCHED_FIFO at priority {}", thread, priority);
  const std::string refused = fmt::format(
      "SCHED_FIFO refused (needs CAP_SYS_NICE or ulimit -r {}); the {} runs time-shared", priority,
      thread);
  return backbone_log.find(granted) != std::string::npos ||
         backbone_log.find(refused) != std::string::npos;
}

LineSetData probeLineSet(const std::string& robot_id, uint32_t sequence, int segments) {
  LineSetData data;
  data.robot_id = robot_id;
  data.sequence_number = sequence;
  data.stamp_ns = wallClockNs();
  data.camera = {500, 500, 320, 240, 0, 640, 480};
  data.segments.resize(segments);
  for (ImageSegment& segment : data.segments) {
    segment.start = {10, 10};
    segment.end = {200, 10};
  }
  data.predicted_T_world_camera.pose = makePose({5, -20, 1.5}, Eigen::Quaterniond::Identity());
  // Close enough to be tracked rather than searched for.
  data.predicted_T_world_camera.covariance = diagonalPoseCovariance(0.05, 0.005);
  return data;
}

class RobotBackboneLoop : public ::testing::Test {
 protected:
  void SetUp() override {
    work_ = fs::temp_directory_path() / ("loop_" + std::to_string(getpid()));
    fs::remove_all(work_);
    writeFacadeFrames(work_ / "images", kFrames);
    writeCalibration(work_ / "camera.yml");
    test::insertCubeBuilding(database_.conninfo(), 85000, 447000, 0, 0);
  }
  void TearDown() override { fs::remove_all(work_); }

  std::unique_ptr<test::ChildProcess> startBackbone() {
    return startBackbone(work_ / "stats.json");
  }

  std::unique_ptr<test::ChildProcess> startBackbone(
      const fs::path& stats_file, const std::vector<std::string>& more_options = {}) {
    return start("lineloc-backbone", "backbone-test", "backbone.log",
                 {"--db", database_.conninfo(test::DatabaseRole::kReader), "--site", "test",
                  "--max-segments", std::to_string(kBackboneMaxSegments), "--stats-file",
                  stats_file.string(), "--stats-period-s", "0.1"},
                 more_options);
  }

  std::unique_ptr<test::ChildProcess> startRobot(
      const std::string& robot_id, double rate_hz,
      const std::vector<std::string>& more_options = {}) {
    return start("lineloc-robot", "robot-" + robot_id, robot_id + ".log",
                 {"--robot-id",
                  robot_id,
                  "--images",
                  (work_ / "images").string(),
                  "--camera-calibration",
                  (work_ / "camera.yml").string(),
                  "--predicted-pose",
                  "5",
                  "-20",
                  "1.5",
                  "0",
                  "0",
                  "0",
                  "1",
                  "--rate-hz",
                  std::to_string(rate_hz),
                  "--trajectory-out",
                  (work_ / (robot_id + ".tum")).string(),
                  "--fused-trajectory-out",
                  (work_ / (robot_id + "-fused.tum")).string(),
                  "--fix-timeout-s",
                  "3"},
                 more_options);
  }

  // Issues DDS Security identities for the backbone and `robot_ids`: from
  // then on they start secured.
  void secure(const std::vector<std::string>& robot_ids) {
    security_overlays_["backbone-test"] = test::issueDdsIdentity(pki(), "backbone", "test");
    for (const std::string& robot_id : robot_ids) {
      security_overlays_["robot-" + robot_id] = test::issueDdsIdentity(pki(), "robot", robot_id);
    }
  }
  std::string pki() const { return (work_ / "pki").string(); }
  // The DDS configuration of `participant` ("backbone-test", "robot-<id>"):
  // the test's, secured with its identity when it has one.
  std::string ddsConfigOf(const std::string& participant) const {
    const auto overlay = security_overlays_.find(participant);
    return test::testDdsConfig() +
           (overlay == security_overlays_.end() ? std::string() : "," + overlay->second);
  }

  // `program` as DDS `participant` on the test's domain with `options`, then `more_options`.
  std::unique_ptr<test::ChildProcess> start(const std::string& program,
                                            const std::string& participant, const std::string& log,
                                            std::vector<std::string> options,
                                            const std::vector<std::string>& more_options) {
    options.insert(options.begin(), {"--domain-id", std::to_string(test::testDomainId()),
                                     "--dds-config", ddsConfigOf(participant)});
    options.insert(options.end(), more_options.begin(), more_options.end());
    return std::make_unique<test::ChildProcess>(std::string(LINELOC_BIN_DIR) + "/" + program,
                                                options, (work_ / log).string());
  }

  // The backbone's counters; an empty object until its first stats file exists.
  nlohmann::json stats() const {
    std::ifstream stream(work_ / "stats.json");
    nlohmann::json parsed = stream ? nlohmann::json::parse(stream, nullptr, false) : nullptr;
    return parsed.is_object() ? parsed : nlohmann::json::object();
  }

  std::string log(const std::string& name) const {
    std::ifstream stream(work_ / name);
    return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
  }

  test::TestDatabase database_{"loop"};
  fs::path work_;
  std::map<std::string, std::string> security_overlays_;
};

TEST_F(RobotBackboneLoop, EveryFrameOfEveryRobotGetsExactlyOneMatchingFix) {
  Observer observer;
  // Its answering threads under SCHED_FIFO when the machine allows it.
  auto backbone = startBackbone(work_ / "stats.json", {"--realtime-priority", "3"});
  ASSERT_TRUE(observer.pollUntil([&] { return observer.backboneListening(); }))
      << log("backbone.log");

  // Malformed LineSets first: each is dropped and counted, none answered.
  LineSetData nan_segment = probeLineSet(kProbeRobot, 1, 5);
  nan_segment.segments[3].start.x() = std::numeric_limits<float>::quiet_NaN();
  LineSetData oversized = probeLineSet(kProbeRobot, 2, kBackboneMaxSegments + 500);
  for (LineSetData* bad : {&nan_segment, &oversized}) {
    observer.writer().write(LineSetMessage(*bad).message());
  }
  // A LineSet for another robot than the one of the partition it is written
  // in, well-formed or not, is refused before it is handled; so is such an
  // exposure notice, on its own topic and thread.
  const LineSetData bad_robot_id = probeLineSet("bad id!", 3, 5);
  const LineSetData another_robots = probeLineSet("another-robot", 3, 5);
  observer.writer().write(LineSetMessage(bad_robot_id).message());
  observer.writer().write(LineSetMessage(another_robots).message());
  observer.exposureWriter().write(LineSetMessage(another_robots).message());
  // The next good one is answered at once, without a pose while the map
  // around it is prepared.
  observer.writer().write(LineSetMessage(probeLineSet(kProbeRobot, 4, 5)).message());
  ASSERT_TRUE(observer.pollUntil([&] { return observer.fixesFor(kProbeRobot) > 0; }))
      << log("backbone.log");
  ASSERT_EQ(observer.fixes.size(), 1u);
  EXPECT_EQ(observer.fixes[0].sequence_number, 4u);
  EXPECT_EQ(observer.fixes[0].status, lineloc_msg_FIX_NO_MATCH_COMPUTED);
  // Once it is, the probe's segments, which match no building, are answered
  // as such rather than with a guess.
  uint32_t sequence = 4;
  do {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    observer.writer().write(LineSetMessage(probeLineSet(kProbeRobot, ++sequence, 5)).message());
    ASSERT_TRUE(observer.pollUntil([&] {
      return observer.fixes.back().sequence_number == sequence;
    })) << log("backbone.log");
  } while (observer.fixes.back().status == lineloc_msg_FIX_NO_MATCH_COMPUTED && sequence < 100);
  EXPECT_EQ(observer.fixes.back().model_lines, 12u);
  EXPECT_EQ(observer.fixes.back().status, lineloc_msg_FIX_TOO_FEW_MATCHES);
  const int probes_answered = static_cast<int>(sequence) - 3;
  ASSERT_TRUE(observer.pollUntil([&] { return stats().value("answered", 0) == probes_answered; }));
  ASSERT_TRUE(observer.pollUntil([&] { return stats().value("dropped_invalid", 0) == 5; }))
      << log("backbone.log");
  EXPECT_EQ(stats()["received"], probes_answered + 2) << "the refused ones are not received";
  EXPECT_EQ(observer.fixesFor("another-robot"), 0u);
  EXPECT_NE(log("backbone.log")
                .find("robot_id 'another-robot' written outside partition "
                      "'robot.another-robot'"),
            std::string::npos);

  // Two robots at once, one extracting under SCHED_FIFO when the machine
  // allows it.
  auto robot_a = startRobot("robot-a", 20.0);
  auto robot_b = startRobot("robot-b", 25.0, {"--realtime-priority", "5"});
  ASSERT_EQ(robot_a->wait(kTimeoutMs), 0) << log("robot-a.log");
  ASSERT_EQ(robot_b->wait(kTimeoutMs), 0) << log("robot-b.log");
  const std::string robot_b_log = log("robot-b.log");
  EXPECT_TRUE(robot_b_log.find("under SCHED_FIFO at priority 5") != std::string::npos ||
              robot_b_log.find("SCHED_FIFO refused") != std::string::npos)
      << robot_b_log;
  observer.pollUntil([&] {
    return observer.fixesFor("robot-a") == kFrames && observer.fixesFor("robot-b") == kFrames;
  });

  for (const std::string robot_id : {"robot-a", "robot-b"}) {
    // The observer meets each robot's participant on its own, and under load
    // after the robot has met the backbone: it may miss the first frames a
    // robot sends (1 of 10 runs beside a Delft drive), never a later one.
    const auto& stamps = observer.sent_stamps[robot_id];
    ASSERT_FALSE(stamps.empty()) << robot_id;
    const uint32_t first_seen = stamps.begin()->first;
    EXPECT_EQ(stamps.size(), static_cast<size_t>(kFrames) - first_seen) << robot_id;
    std::set<uint32_t> answered;
    for (const PoseFixData& fix : observer.fixes) {
      if (fix.robot_id != robot_id)
        continue;
      EXPECT_TRUE(answered.insert(fix.sequence_number).second)
          << robot_id << " frame " << fix.sequence_number << " answered twice";
      EXPECT_EQ(fix.model_lines, 12u);
      if (fix.sequence_number < first_seen) {
        continue;
      }
      ASSERT_TRUE(stamps.count(fix.sequence_number)) << "fix for a frame never sent";
      EXPECT_EQ(fix.stamp_ns, stamps.at(fix.sequence_number));
    }
    EXPECT_EQ(answered, frameIndices()) << robot_id;
    // The robot took one answer per frame; none carried a pose (the façades
    // are no building of the model), so its fix trajectory stays empty.
    EXPECT_EQ(fixesReceived(log(robot_id + ".log")), kFrames) << log(robot_id + ".log");
    EXPECT_TRUE(readTumFile((work_ / (robot_id + ".tum")).string()).empty());
    // Its latency split: extraction and the backbone's matching take time,
    // and the DDS legs either way, timed on one host's clock, are not negative.
    const std::vector<double> medians_ms = latencyStageMedians(log(robot_id + ".log"));
    ASSERT_EQ(medians_ms.size(), 4u) << log(robot_id + ".log");
    EXPECT_GT(medians_ms[0], 0.0);
    EXPECT_GE(medians_ms[1], 0.0);
    EXPECT_GT(medians_ms[2], 0.0);
    EXPECT_GE(medians_ms[3], 0.0);
  }
  backbone->signal(SIGTERM);
  EXPECT_EQ(backbone->wait(kTimeoutMs), 0) << log("backbone.log");
  for (const std::string thread : {"LineSets' thread", "exposure notices' thread"}) {
    EXPECT_TRUE(askedForRealtimePriority(log("backbone.log"), thread, 3)) << log("backbone.log");
  }
}

TEST_F(RobotBackboneLoop, RobotSurvivesTheBackboneBeingKilledMidRun) {
  Observer observer;
  auto backbone = startBackbone();
  ASSERT_TRUE(observer.pollUntil([&] { return observer.backboneListening(); }));
  auto robot = startRobot("robot-c", 8.0);  // 12 frames take 1.5 s
  ASSERT_TRUE(observer.pollUntil([&] { return observer.fixesFor("robot-c") >= 3; }));
  backbone->signal(SIGKILL);
  EXPECT_EQ(backbone->wait(kTimeoutMs), 128 + SIGKILL);
  ASSERT_EQ(robot->wait(kTimeoutMs), 0) << log("robot-c.log");
  // Fixes in flight when the backbone died may or may not have reached the robot.
  const int received = fixesReceived(log("robot-c.log"));
  EXPECT_GE(received, 1) << log("robot-c.log");
  EXPECT_LT(received, kFrames);
  observer.poll();
  const auto& stamps = observer.sent_stamps["robot-c"];
  ASSERT_FALSE(stamps.empty());
  EXPECT_EQ(stamps.rbegin()->first, static_cast<uint32_t>(kFrames - 1))
      << "the robot must keep sending after the backbone is gone";
  EXPECT_EQ(stamps.size(), static_cast<size_t>(kFrames) - stamps.begin()->first);
}

// A frame that cannot be decoded is skipped, counted and named in the log;
// the robot goes on with the next one and every other frame is answered.
TEST_F(RobotBackboneLoop, ARobotSkipsACorruptFrameAndGoesOn) {
  std::ofstream(work_ / "images" / "frame003.png", std::ios::trunc) << "not a PNG";
  Observer observer;
  auto backbone = startBackbone();
  ASSERT_TRUE(observer.pollUntil([&] { return observer.backboneListening(); }))
      << log("backbone.log");
  auto robot = startRobot("robot-e", 20.0);
  ASSERT_EQ(robot->wait(kTimeoutMs), 0) << log("robot-e.log");
  const std::string robot_log = log("robot-e.log");
  EXPECT_NE(robot_log.find("skipped frame 3: "), std::string::npos) << robot_log;
  EXPECT_NE(robot_log.find("frame003.png"), std::string::npos) << robot_log;
  EXPECT_NE(robot_log.find("1 skipped as their image was missing or corrupt"), std::string::npos)
      << robot_log;
  EXPECT_EQ(fixesReceived(robot_log), kFrames - 1) << robot_log;
  backbone->signal(SIGTERM);
  EXPECT_EQ(backbone->wait(kTimeoutMs), 0) << log("backbone.log");
}

// A dataset without the IMU that would carry its pose is refused at the
// start, saying so, instead of a run that never localises.
TEST_F(RobotBackboneLoop, ADatasetWithoutItsIMUFailsTheRobotsStart) {
  const fs::path dataset = work_ / "dataset";
  writeTimedCameraFolder(dataset);
  auto robot = start("lineloc-robot", "robot-robot-f", "robot-f.log",
                     {"--robot-id", "robot-f", "--images", dataset.string(), "--camera-calibration",
                      (work_ / "camera.yml").string()},
                     {});
  EXPECT_EQ(robot->wait(kTimeoutMs), 1) << log("robot-f.log");
  EXPECT_NE(log("robot-f.log").find("has no IMU stream"), std::string::npos) << log("robot-f.log");
}

// A robot with an IMU and no GNSS needs to be told where it starts: without
// a start pose it refuses to start, saying so; with one it starts there once
// it has stood through the alignment window, and its first frame's
// prediction is where it was told.
TEST_F(RobotBackboneLoop, ARobotWithoutGnssStartsFromTheStartPoseItIsGiven) {
  const fs::path dataset = work_ / "dataset";
  writeTimedCameraFolder(dataset);
  writeStandingImu(dataset);
  const std::vector<std::string> options = {"--robot-id",
                                            "robot-g",
                                            "--images",
                                            dataset.string(),
                                            "--camera-calibration",
                                            (work_ / "camera.yml").string(),
                                            "--wait-for-backbone-s",
                                            "0",
                                            "--fused-trajectory-out",
                                            (work_ / "robot-g-fused.tum").string(),
                                            "--trajectory-out",
                                            (work_ / "robot-g.tum").string(),
                                            "--fix-timeout-s",
                                            "0.1"};
  auto refused = start("lineloc-robot", "robot-robot-g", "robot-g.log", options, {});
  EXPECT_EQ(refused->wait(kTimeoutMs), 1) << log("robot-g.log");
  EXPECT_NE(log("robot-g.log").find("has no DGPS stream"), std::string::npos) << log("robot-g.log");

  // The body level, the camera looking along it (InertialNavigatorConfig).
  const Eigen::Isometry3d T_world_camera =
      makePose({5.0, -20.0, 0.3}, Eigen::Quaterniond::Identity()) *
      InertialNavigatorConfig::defaultBodyCamera();
  const Eigen::Quaterniond q(T_world_camera.linear());
  std::vector<std::string> start_pose = {"--start-pose"};
  for (const double value : {T_world_camera.translation().x(), T_world_camera.translation().y(),
                             T_world_camera.translation().z(), q.x(), q.y(), q.z(), q.w()}) {
    start_pose.push_back(fmt::format("{:.17g}", value));
  }
  auto robot = start("lineloc-robot", "robot-robot-g", "robot-g.log", options, start_pose);
  ASSERT_EQ(robot->wait(kTimeoutMs), 0) << log("robot-g.log");
  const std::vector<StampedPose> fused = readTumFile((work_ / "robot-g-fused.tum").string());
  ASSERT_EQ(fused.size(), 3u) << log("robot-g.log");
  EXPECT_LT((fused.front().pose.translation() - T_world_camera.translation()).norm(), 0.01);
  EXPECT_LT(
      Eigen::AngleAxisd(fused.front().pose.linear().transpose() * T_world_camera.linear()).angle(),
      1e-3);
}

// A robot on ROS 2: its IMU and camera from ROS 2 topics (sensor_msgs/Imu,
// sensor_msgs/Image), told where it starts; its state published for ROS 2,
// base_link's pose in map as Foxglove's ROS 2 implementation decodes it,
// where the robot stands.
TEST_F(RobotBackboneLoop, ARobotOnRos2TopicsTakesItsSensorsAndPublishesItsState) {
  const dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  const dds::Participant participant(domain);
  dds::Writer<sensor_msgs_msg_dds__Imu_> imu(participant, dds::Qos(64), "", "rt/imu/data");
  dds::Writer<sensor_msgs_msg_dds__Image_> camera(participant, dds::Qos(8), "",
                                                  "rt/camera/image_raw");
  test::SerializedReader poses(participant, geometry_msgs_msg_dds__PoseWithCovarianceStamped__desc,
                               "rt/lineloc/pose");
  const Eigen::Isometry3d T_world_camera =
      makePose({5.0, -20.0, 0.3}, Eigen::Quaterniond::Identity()) *
      InertialNavigatorConfig::defaultBodyCamera();
  const Eigen::Quaterniond q(T_world_camera.linear());
  std::vector<std::string> options = {"--robot-id",
                                      "robot-r",
                                      "--camera-calibration",
                                      (work_ / "camera.yml").string(),
                                      "--ros-domain-id",
                                      std::to_string(test::testDomainId()),
                                      "--ros-dds-config",
                                      test::testDdsConfig(),
                                      "--ros-imu-topic",
                                      "/imu/data",
                                      "--ros-image-topic",
                                      "/camera/image_raw",
                                      "--max-frames",
                                      "5",
                                      "--wait-for-backbone-s",
                                      "0",
                                      "--fix-timeout-s",
                                      "0.1",
                                      "--fused-trajectory-out",
                                      (work_ / "robot-r-fused.tum").string(),
                                      "--trajectory-out",
                                      (work_ / "robot-r.tum").string(),
                                      "--start-pose"};
  for (const double value : {T_world_camera.translation().x(), T_world_camera.translation().y(),
                             T_world_camera.translation().z(), q.x(), q.y(), q.z(), q.w()}) {
    options.push_back(fmt::format("{:.17g}", value));
  }
  auto robot = start("lineloc-robot", "robot-robot-r", "robot-r.log", options, {});

  // Standing: 200 Hz of level IMU, and after the 2 s alignment window a
  // frame every 100 ms, until the robot has taken its five.
  const cv::Mat frame =
      cv::imread((work_ / "images" / "frame000.png").string(), cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(frame.empty());
  std::vector<uint8_t> pixels(frame.datastart, frame.dataend);
  const auto start_time = std::chrono::steady_clock::now();
  for (int tick = 0; robot->running() && tick < 200 * 20; ++tick) {
    std::this_thread::sleep_until(start_time + std::chrono::milliseconds(5 * tick));
    const int64_t stamp_ns = wallClockNs();
    sensor_msgs_msg_dds__Imu_ sample{};
    sample.header.stamp = rosTime(stamp_ns);
    sample.header.frame_id = const_cast<char*>("imu");
    sample.linear_acceleration.z = 9.80665;
    imu.write(sample);
    if (tick >= 500 && tick % 20 == 0) {
      sensor_msgs_msg_dds__Image_ image{};
      image.header.stamp = rosTime(stamp_ns);
      image.header.frame_id = const_cast<char*>("camera");
      image.width = static_cast<uint32_t>(frame.cols);
      image.height = static_cast<uint32_t>(frame.rows);
      image.encoding = const_cast<char*>("mono8");
      image.step = static_cast<uint32_t>(frame.cols);
      image.data._buffer = pixels.data();
      image.data._length = static_cast<uint32_t>(pixels.size());
      image.data._maximum = image.data._length;
      camera.write(image);
    }
  }
  ASSERT_EQ(robot->wait(kTimeoutMs), 0) << log("robot-r.log");
  EXPECT_EQ(readTumFile((work_ / "robot-r-fused.tum").string()).size(), 5u) << log("robot-r.log");
  const std::vector<std::vector<uint8_t>> published = poses.take(1'000'000'000);
  ASSERT_FALSE(published.empty()) << log("robot-r.log");
  const nlohmann::json pose =
      test::decodedByFoxglove("geometry_msgs/PoseWithCovarianceStamped", published.back());
  EXPECT_EQ(pose["header"]["frame_id"], "map");
  const nlohmann::json& position = pose["pose"]["pose"]["position"];
  EXPECT_LT((Eigen::Vector3d(position["x"], position["y"], position["z"]) -
             Eigen::Vector3d(5.0, -20.0, 0.3))
                .norm(),
            0.05)
      << pose.dump();
}

TEST_F(RobotBackboneLoop, ARealtimePriorityOutsideOneToNinetyNineFailsTheRobotsStart) {
  auto robot = startRobot("robot-d", 20.0, {"--realtime-priority", "100"});
  EXPECT_EQ(robot->wait(kTimeoutMs), 1) << log("robot-d.log");
  EXPECT_NE(log("robot-d.log").find("realtime_priority 100 must be 0"), std::string::npos)
      << log("robot-d.log");
}

// Hundreds of robots' searches queued (the queue's bound raised to hold them
// all), each around a prior of 5 m sigma, the backbone stops on SIGTERM
// within the test's timeout: the queued searches are dropped and the running
// one cancelled, where running each of them to its end would outlast it.
TEST_F(RobotBackboneLoop, TheBackboneStopsWithHundredsOfSearchesQueued) {
  Observer observer;
  auto backbone = startBackbone(work_ / "stats.json",
                                {"--max-robots", "1000", "--max-queued-searches", "1000"});
  ASSERT_TRUE(observer.pollUntil([&] { return observer.backboneListening(); }))
      << log("backbone.log");
  // The map prepared first, so that the frames below are searched.
  uint32_t sequence = 1;
  do {
    observer.writer().write(LineSetMessage(probeLineSet(kProbeRobot, sequence, 5)).message());
    ASSERT_TRUE(observer.pollUntil([&] { return observer.fixesFor(kProbeRobot) == sequence; }))
        << log("backbone.log");
    ++sequence;
  } while (observer.fixes.back().status == lineloc_msg_FIX_NO_MATCH_COMPUTED && sequence < 100);
  // Each robot writes in its own partition; the backbone and the observer
  // read every robot's.
  constexpr int kSearchedRobots = 300;
  std::vector<std::unique_ptr<dds::Writer<lineloc_msg_LineSet>>> robots;
  for (int robot = 0; robot < kSearchedRobots; ++robot) {
    robots.push_back(std::make_unique<dds::Writer<lineloc_msg_LineSet>>(
        observer.participant(), dds::Qos(dds::kHistoryDepth),
        robotPartition("searched-" + std::to_string(robot))));
  }
  ASSERT_TRUE(observer.pollUntil([&] {
    return std::all_of(robots.begin(), robots.end(),
                       [](const auto& writer) { return writer->matchedReaders() >= 2; });
  })) << log("backbone.log");
  for (int robot = 0; robot < kSearchedRobots; ++robot) {
    LineSetData poor = probeLineSet("searched-" + std::to_string(robot), 1, 5);
    poor.predicted_T_world_camera.pose.linear() << 1, 0, 0, 0, 0, 1, 0, -1, 0;
    poor.predicted_T_world_camera.covariance = diagonalPoseCovariance(5.0, 0.1);
    for (ImageSegment& segment : poor.segments) {
      segment.contrast = 40.0f;
    }
    robots[robot]->write(LineSetMessage(poor).message());
  }
  ASSERT_TRUE(observer.pollUntil([&] {
    return observer.fixes.size() == sequence - 1 + kSearchedRobots;
  })) << log("backbone.log");
  backbone->signal(SIGTERM);
  EXPECT_EQ(backbone->wait(kTimeoutMs), 0) << log("backbone.log");
  EXPECT_LT(stats().value("searches", kSearchedRobots), kSearchedRobots);
}

// A robot that falls silent is forgotten although no other robot sends
// anything that would make the backbone look for silent ones.
TEST_F(RobotBackboneLoop, TheLastRobotLeftIsForgottenInTheSilenceAfterIt) {
  Observer observer;
  auto backbone = startBackbone(work_ / "stats.json", {"--forget-robot-after-s", "0.5"});
  ASSERT_TRUE(observer.pollUntil([&] { return observer.backboneListening(); }))
      << log("backbone.log");
  observer.writer().write(LineSetMessage(probeLineSet(kProbeRobot, 1, 5)).message());
  ASSERT_TRUE(observer.pollUntil([&] { return observer.fixesFor(kProbeRobot) == 1; }))
      << log("backbone.log");
  ASSERT_TRUE(observer.pollUntil([&] { return stats().value("robots_forgotten", 0) == 1; }))
      << log("backbone.log");
  EXPECT_EQ(stats()["robots"], 0);
  EXPECT_NE(log("backbone.log").find("forgetting robot probe"), std::string::npos)
      << log("backbone.log");
  backbone->signal(SIGTERM);
  EXPECT_EQ(backbone->wait(kTimeoutMs), 0) << log("backbone.log");
}

// The stats file is rewritten beside the serving loop, whose answers must not
// wait for the file system; one that cannot be written at all fails the start
// instead of going unnoticed.
TEST_F(RobotBackboneLoop, ARealtimePriorityOutsideOneToNinetyNineFailsTheBackbonesStart) {
  auto backbone = startBackbone(work_ / "stats.json", {"--realtime-priority", "-1"});
  EXPECT_EQ(backbone->wait(kTimeoutMs), 1) << log("backbone.log");
  EXPECT_NE(log("backbone.log").find("realtime_priority -1 must be 0"), std::string::npos)
      << log("backbone.log");
}

TEST_F(RobotBackboneLoop, AStatsFileThatCannotBeWrittenFailsTheStart) {
  auto backbone = startBackbone(work_ / "no such folder" / "stats.json");
  EXPECT_EQ(backbone->wait(kTimeoutMs), 1) << log("backbone.log");
  EXPECT_NE(log("backbone.log").find("cannot write stats file"), std::string::npos)
      << log("backbone.log");
}

// A forged answer for each of the robot's frames: OK, 50 m off, sure to the millimetre.
void forgeFixes(dds::Writer<lineloc_msg_PoseFix>& writer, const std::string& robot_id,
                const std::map<uint32_t, int64_t>& sent_stamps) {
  for (uint32_t sequence = 0; sequence < static_cast<uint32_t>(kFrames); ++sequence) {
    PoseFixData fix;
    fix.robot_id = robot_id;
    fix.sequence_number = sequence;
    const auto stamp = sent_stamps.find(sequence);
    fix.stamp_ns = stamp == sent_stamps.end() ? 0 : stamp->second;
    fix.status = lineloc_msg_FIX_OK;
    fix.T_world_camera.pose = makePose({55, -20, 1.5}, Eigen::Quaterniond::Identity());
    fix.T_world_camera.covariance = diagonalPoseCovariance(0.001, 0.0001);
    writer.write(toMessage(fix));
  }
}

// An outsider (no identity) on the domain of a secured robot and backbone
// hears nothing and is heard by no one: the forged answers it writes for
// every frame never reach the robot, which gets its backbone's answers only.
TEST_F(RobotBackboneLoop, OnASecuredDomainAnOutsiderNeitherHearsNorSteersTheRobot) {
  secure({"robot-s"});
  Observer outsider;
  dds::Writer<lineloc_msg_PoseFix> forged(outsider.participant(), dds::poseFixQos(kFrames),
                                          robotPartition("robot-s"));
  auto backbone = startBackbone();
  auto robot = startRobot("robot-s", 8.0);
  while (robot->running()) {
    forgeFixes(forged, "robot-s", outsider.sent_stamps["robot-s"]);
    outsider.poll();
  }
  ASSERT_EQ(robot->wait(kTimeoutMs), 0) << log("robot-s.log");
  EXPECT_EQ(fixesReceived(log("robot-s.log")), kFrames) << log("robot-s.log");
  EXPECT_EQ(log("robot-s.log").find("dropped a PoseFix"), std::string::npos) << log("robot-s.log");
  for (const dds::ParticipantGuid& reader : forged.matchedReaderParticipants()) {
    EXPECT_EQ(reader, outsider.participant().guid()) << "a forged answer reached another reader";
  }
  EXPECT_TRUE(outsider.sent_stamps["robot-s"].empty()) << "the outsider heard the robot";
  for (const PoseFixData& fix : outsider.fixes) {
    EXPECT_EQ(fix.T_world_camera.pose.translation().x(), 55.0) << "the outsider heard the backbone";
  }
  EXPECT_NE(log("backbone.log").find("DDS Security on"), std::string::npos) << log("backbone.log");
}

// The same outsider on an unsecured domain hears the robot's frames and
// answers them: what the secured domain prevents.
TEST_F(RobotBackboneLoop, OnAnUnsecuredDomainTheSameOutsiderHearsAndAnswersTheRobot) {
  Observer outsider;
  dds::Writer<lineloc_msg_PoseFix> forged(outsider.participant(), dds::poseFixQos(kFrames),
                                          robotPartition("robot-u"));
  auto robot = startRobot("robot-u", 8.0, {"--wait-for-backbone-s", "0"});
  while (robot->running()) {
    forgeFixes(forged, "robot-u", outsider.sent_stamps["robot-u"]);
    outsider.poll();
  }
  ASSERT_EQ(robot->wait(kTimeoutMs), 0) << log("robot-u.log");
  EXPECT_FALSE(outsider.sent_stamps["robot-u"].empty());
  EXPECT_GT(fixesReceived(log("robot-u.log")), 0) << log("robot-u.log");
  EXPECT_NE(log("robot-u.log").find("DDS Security is off"), std::string::npos)
      << log("robot-u.log");
}

// A robot's identity grants its own partition and nothing else: it can
// neither speak nor listen for another robot, nor answer as a backbone; in
// its own partition the backbone answers it. Revoked, it is refused by
// participants started after the revocation.
TEST_F(RobotBackboneLoop, ASecuredRobotSpeaksAndListensOnlyForItself) {
  secure({"robot-s", "robot-t"});
  {
    dds::Domain domain(test::testDomainId(), ddsConfigOf("robot-robot-t"));
    dds::Participant robot_t(domain);
    const dds::Qos qos(dds::kHistoryDepth);
    const dds::Qos fix_qos = dds::poseFixQos(dds::kHistoryDepth);
    using LineSets = dds::Writer<lineloc_msg_LineSet>;
    using Fixes = dds::Reader<lineloc_msg_PoseFix>;
    EXPECT_THROW(LineSets(robot_t, qos, robotPartition("robot-s")), dds::DdsError);
    EXPECT_THROW(Fixes(robot_t, fix_qos, robotPartition("robot-s")), dds::DdsError);
    EXPECT_THROW(Fixes(robot_t, fix_qos, kEveryRobotPartition), dds::DdsError);
    EXPECT_THROW(dds::Reader<lineloc_msg_LineSet>(robot_t, qos, kEveryRobotPartition),
                 dds::DdsError);
    EXPECT_THROW(dds::Writer<lineloc_msg_PoseFix>(robot_t, fix_qos, robotPartition("robot-t")),
                 dds::DdsError);

    auto backbone = startBackbone();
    LineSets own(robot_t, qos, robotPartition("robot-t"));
    Fixes own_fixes(robot_t, fix_qos, robotPartition("robot-t"));
    const int64_t deadline = steadyClockNs() + int64_t{kTimeoutMs} * 1'000'000;
    uint32_t sequence = 0;
    bool answered = false;
    while (!answered && steadyClockNs() < deadline) {
      own.write(LineSetMessage(probeLineSet("robot-t", ++sequence, 5)).message());
      own_fixes.waitForData(100'000'000);
      own_fixes.takeEach([&](const lineloc_msg_PoseFix& fix) {
        answered |= std::string(fix.robot_id) == "robot-t";
      });
    }
    EXPECT_TRUE(answered) << log("backbone.log");
    backbone->signal(SIGTERM);
    EXPECT_EQ(backbone->wait(kTimeoutMs), 0) << log("backbone.log");
  }
  // Revoked, robot-t still holds the revocation list of before.
  const fs::path crl_before = work_ / "crl-before.pem";
  fs::copy_file(fs::path(pki()) / "ca" / "crl.pem", crl_before);
  test::revokeDdsIdentity(pki(), "robot", "robot-t");
  std::string overlay_text = log("pki/identities/robot-robot-t/cyclonedds-security.xml");
  const std::string crl_now = "file:" + (fs::path(pki()) / "ca" / "crl.pem").string();
  overlay_text.replace(overlay_text.find(crl_now), crl_now.size(), "file:" + crl_before.string());
  std::ofstream(work_ / "revoked.xml") << overlay_text;
  dds::Domain domain(test::testDomainId(),
                     test::testDdsConfig() + "," + (work_ / "revoked.xml").string());
  dds::Participant revoked(domain);
  dds::Writer<lineloc_msg_LineSet> line_sets(revoked, dds::Qos(dds::kHistoryDepth),
                                             robotPartition("robot-t"));
  auto backbone = startBackbone();
  auto robot_s = startRobot("robot-s", 8.0);
  ASSERT_EQ(robot_s->wait(kTimeoutMs), 0) << log("robot-s.log");
  EXPECT_EQ(fixesReceived(log("robot-s.log")), kFrames) << "the backbone is up and serving";
  EXPECT_EQ(line_sets.matchedReaders(), 0u) << "the backbone authenticated a revoked robot";
}

// A flood from inside the domain (a faulty robot, or one whose identity was
// stolen): one robot id sends 4,096-segment LineSets in bursts of three every
// 10 ms and fifteen more send them at 10 Hz, each valid and tracked in a
// prepared map. Beside it a robot at 10 Hz has every frame answered and none
// FIX_BUSY (fair_frame_queue.h); the flood's excess (of each burst, one frame
// at most is answered while the next waits) is superseded or late, answered
// FIX_BUSY and counted; the backbone's memory stays bounded, and it stops
// when asked.
// The robot's latency with and without the flood is printed, not asserted.
TEST_F(RobotBackboneLoop, AFloodFromSixteenRobotIdsLeavesAnotherRobotAnsweredOnEveryFrame) {
  constexpr int kFloodIds = 16;
  constexpr int kFloodSegments = 4096;
  auto backbone = start("lineloc-backbone", "backbone-test", "backbone.log",
                        {"--db", database_.conninfo(test::DatabaseRole::kReader), "--site", "test",
                         "--max-segments", std::to_string(kFloodSegments), "--stats-file",
                         (work_ / "stats.json").string(), "--stats-period-s", "0.1"},
                        {});
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant flooder(domain);
  dds::Reader<lineloc_msg_PoseFix> fixes(flooder, dds::poseFixQos(256), kEveryRobotPartition);
  std::vector<std::unique_ptr<dds::Writer<lineloc_msg_LineSet>>> writers;
  std::vector<std::unique_ptr<LineSetMessage>> frames;
  std::mt19937 random(81);
  std::uniform_real_distribution<float> x_px(0.0f, 639.0f);
  std::uniform_real_distribution<float> y_px(0.0f, 479.0f);
  for (int id = 0; id < kFloodIds; ++id) {
    const std::string robot_id = "flood-" + std::to_string(id);
    writers.push_back(std::make_unique<dds::Writer<lineloc_msg_LineSet>>(
        flooder, dds::Qos(dds::kHistoryDepth), robotPartition(robot_id)));
    LineSetData frame = probeLineSet(robot_id, 0, kFloodSegments);
    for (ImageSegment& segment : frame.segments) {
      segment.start = {x_px(random), y_px(random)};
      segment.end = {x_px(random), y_px(random)};
      segment.contrast = 30.0f;
    }
    frames.push_back(std::make_unique<LineSetMessage>(frame));
  }
  std::vector<uint32_t> sequence(kFloodIds, 0);
  std::map<std::string, std::vector<lineloc_msg_FixStatus>> statuses;
  const auto send = [&](int id) {
    lineloc_msg_LineSet message = frames[id]->message();
    message.sequence_number = ++sequence[id];
    message.stamp_ns = wallClockNs();
    writers[id]->write(message);
  };
  const auto takeFixes = [&](int64_t wait_ns) {
    fixes.waitForData(wait_ns);
    fixes.takeEach(
        [&](const lineloc_msg_PoseFix& fix) { statuses[fix.robot_id].push_back(fix.status); });
  };
  // The map prepared first, so that the flood is tracked.
  const int64_t deadline = steadyClockNs() + int64_t{kTimeoutMs} * 1'000'000;
  while ((statuses["flood-0"].empty() ||
          statuses["flood-0"].back() == lineloc_msg_FIX_NO_MATCH_COMPUTED) &&
         steadyClockNs() < deadline) {
    send(0);
    takeFixes(50'000'000);
  }
  ASSERT_FALSE(statuses["flood-0"].empty()) << log("backbone.log");
  ASSERT_NE(statuses["flood-0"].back(), lineloc_msg_FIX_NO_MATCH_COMPUTED) << log("backbone.log");

  auto quiet = startRobot("robot-q", 10.0);
  ASSERT_EQ(quiet->wait(kTimeoutMs), 0) << log("robot-q.log");

  std::atomic<bool> flooding = true;
  std::jthread flood([&] {
    for (int64_t tick = 0; flooding; ++tick) {
      for (int burst = 0; burst < 3; ++burst) {
        send(0);
      }
      if (tick % 10 == 0) {
        for (int id = 1; id < kFloodIds; ++id) {
          send(id);
        }
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  });
  auto robot = startRobot("robot-f", 10.0);
  while (robot->running()) {
    takeFixes(10'000'000);
  }
  flooding = false;
  flood.join();
  ASSERT_EQ(robot->wait(kTimeoutMs), 0) << log("robot-f.log");
  const int64_t backbone_peak_kib = backbone->peakResidentKiB();
  backbone->signal(SIGTERM);
  EXPECT_EQ(backbone->wait(kTimeoutMs), 0) << log("backbone.log");
  takeFixes(0);

  EXPECT_EQ(fixesReceived(log("robot-f.log")), kFrames) << log("robot-f.log");
  EXPECT_EQ(
      std::count(statuses["robot-f"].begin(), statuses["robot-f"].end(), lineloc_msg_FIX_BUSY), 0);
  uint32_t flood_sent = 0;
  for (const uint32_t sent : sequence) {
    flood_sent += sent;
  }
  const nlohmann::json counters = stats();
  const int busy_frames = counters.value("superseded_frames", 0) + counters.value("late_frames", 0);
  EXPECT_GT(busy_frames, 0) << counters.dump();
  EXPECT_LT(backbone_peak_kib, kMaxFloodedBackboneKiB);
  const std::vector<double> quiet_ms = latencyStageMedians(log("robot-q.log"));
  const std::vector<double> flooded_ms = latencyStageMedians(log("robot-f.log"));
  ASSERT_EQ(quiet_ms.size(), 4u);
  ASSERT_EQ(flooded_ms.size(), 4u);
  fmt::print(
      "flood: {} LineSets of {} segments sent, {} superseded or late; backbone peak {} MiB; the "
      "robot's medians (front end, to the backbone, backbone, back): {} ms quiet, {} ms "
      "flooded\n",
      flood_sent, kFloodSegments, busy_frames, backbone_peak_kib / 1024, fmt::join(quiet_ms, "/"),
      fmt::join(flooded_ms, "/"));
}

// Two backbones on one domain share four robots, two each (robot_assignment.h):
// every frame is answered once, by its robot's backbone. One killed
// (SIGKILL), the other answers its robots too once the killed one's
// liveliness lease (1 s) has run out, each frame again once; restarted, it
// takes them back without a frame left unanswered.
TEST_F(RobotBackboneLoop, TwoBackbonesShareTheRobotsAndOneTakesOverWhenTheOtherIsKilled) {
  const auto backbone = [&](const std::string& name) {
    return start("lineloc-backbone", "backbone-test", name + ".log",
                 {"--db", database_.conninfo(test::DatabaseRole::kReader), "--site", "test",
                  "--backbone-name", name, "--stats-file", (work_ / (name + ".json")).string(),
                  "--stats-period-s", "0.1"},
                 {});
  };
  const auto statsOf = [&](const std::string& name) {
    std::ifstream stream(work_ / (name + ".json"));
    nlohmann::json parsed = stream ? nlohmann::json::parse(stream, nullptr, false) : nullptr;
    return parsed.is_object() ? parsed : nlohmann::json::object();
  };
  auto east = backbone("east");
  auto west = backbone("west");
  Observer observer;
  ASSERT_TRUE(observer.pollUntil([&] {
    return statsOf("east").value("backbones", 0) == 2 && statsOf("west").value("backbones", 0) == 2;
  })) << log("east.log")
      << log("west.log");

  // Two robots of each backbone.
  const std::vector<std::string> backbones = {"east", "west"};
  std::vector<std::string> robot_ids;
  std::map<std::string, int> share;
  for (int candidate = 0; robot_ids.size() < 4; ++candidate) {
    const std::string robot_id = "shared-" + std::to_string(candidate);
    if (share[servingBackbone(robot_id, backbones)] < 2) {
      ++share[servingBackbone(robot_id, backbones)];
      robot_ids.push_back(robot_id);
    }
  }
  std::vector<std::unique_ptr<dds::Writer<lineloc_msg_LineSet>>> writers;
  for (const std::string& robot_id : robot_ids) {
    writers.push_back(std::make_unique<dds::Writer<lineloc_msg_LineSet>>(
        observer.participant(), dds::Qos(dds::kHistoryDepth), robotPartition(robot_id)));
  }
  ASSERT_TRUE(observer.pollUntil([&] {
    return std::all_of(writers.begin(), writers.end(),
                       [](const auto& writer) { return writer->matchedReaders() >= 3; });
  }));
  uint32_t sequence = 0;
  const auto sendAll = [&] {
    ++sequence;
    for (size_t robot = 0; robot < robot_ids.size(); ++robot) {
      writers[robot]->write(LineSetMessage(probeLineSet(robot_ids[robot], sequence, 5)).message());
    }
  };
  // Every frame sent from `first` to `last` answered exactly once.
  const auto expectAnsweredOnce = [&](uint32_t first, uint32_t last) {
    for (const std::string& robot_id : robot_ids) {
      std::map<uint32_t, int> answers;
      for (const PoseFixData& fix : observer.fixes) {
        if (fix.robot_id == robot_id && fix.sequence_number >= first &&
            fix.sequence_number <= last) {
          ++answers[fix.sequence_number];
        }
      }
      EXPECT_EQ(answers.size(), last - first + 1) << robot_id;
      for (const auto& [frame, count] : answers) {
        EXPECT_EQ(count, 1) << robot_id << " frame " << frame;
      }
    }
  };
  constexpr uint32_t kFramesEach = 10;
  for (uint32_t frame = 0; frame < kFramesEach; ++frame) {
    sendAll();
    observer.pollUntil([] { return false; }, 50);
  }
  ASSERT_TRUE(
      observer.pollUntil([&] { return observer.fixes.size() >= robot_ids.size() * kFramesEach; }));
  observer.pollUntil([] { return false; }, 300);
  expectAnsweredOnce(1, kFramesEach);
  EXPECT_EQ(statsOf("east").value("frames_served_elsewhere", 0), 2 * kFramesEach);
  EXPECT_EQ(statsOf("west").value("frames_served_elsewhere", 0), 2 * kFramesEach);

  east->signal(SIGKILL);
  const int64_t killed_ns = steadyClockNs();
  std::string east_robot;
  for (const std::string& robot_id : robot_ids) {
    if (servingBackbone(robot_id, backbones) == "east") {
      east_robot = robot_id;
    }
  }
  const uint32_t after_kill = sequence + 1;
  std::optional<int64_t> taken_over_ns;
  ASSERT_TRUE(observer.pollUntil([&] {
    sendAll();
    observer.pollUntil([] { return false; }, 50);
    for (const PoseFixData& fix : observer.fixes) {
      if (fix.robot_id == east_robot && fix.sequence_number >= after_kill && !taken_over_ns) {
        taken_over_ns = steadyClockNs();
      }
    }
    return taken_over_ns && steadyClockNs() > *taken_over_ns + 500'000'000;
  })) << log("west.log");
  const uint32_t taken_over_from = sequence;
  for (int frame = 0; frame < 10; ++frame) {
    sendAll();
    observer.pollUntil([] { return false; }, 50);
  }
  observer.pollUntil([] { return false; }, 300);
  expectAnsweredOnce(taken_over_from, sequence);
  EXPECT_EQ(statsOf("west").value("backbones", 0), 1);
  fmt::print("takeover: the killed backbone's robots answered again {:.2f} s after the kill\n",
             (*taken_over_ns - killed_ns) * 1e-9);

  // Restarted, east takes its robots back; every frame is still answered,
  // once each once both see each other.
  const int west_elsewhere = statsOf("west").value("frames_served_elsewhere", 0);
  east = backbone("east");
  const uint32_t restarted_from = sequence + 1;
  ASSERT_TRUE(observer.pollUntil([&] {
    sendAll();
    observer.pollUntil([] { return false; }, 50);
    return statsOf("east").value("backbones", 0) == 2 && statsOf("west").value("backbones", 0) == 2;
  })) << log("east.log");
  const uint32_t shared_again_from = sequence + 1;
  for (int frame = 0; frame < 10; ++frame) {
    sendAll();
    observer.pollUntil([] { return false; }, 50);
  }
  observer.pollUntil([] { return false; }, 300);
  for (const std::string& robot_id : robot_ids) {
    std::set<uint32_t> answered;
    for (const PoseFixData& fix : observer.fixes) {
      if (fix.robot_id == robot_id && fix.sequence_number >= restarted_from) {
        answered.insert(fix.sequence_number);
      }
    }
    EXPECT_EQ(answered.size(), sequence - restarted_from + 1) << robot_id << ": a frame unanswered";
  }
  expectAnsweredOnce(shared_again_from, sequence);
  EXPECT_GE(statsOf("west").value("frames_served_elsewhere", 0), west_elsewhere + 2 * 10);
  for (auto* process : {&east, &west}) {
    (*process)->signal(SIGTERM);
    EXPECT_EQ((*process)->wait(kTimeoutMs), 0);
  }
}

}  // namespace
}  // namespace lineloc
