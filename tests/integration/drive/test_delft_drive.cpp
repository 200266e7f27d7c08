// The README's main job, shortened: the bundled Delft model loaded into a real
// PostGIS database, a 30 s simulated drive (DGPS + compass start, parked cars,
// trees, pedestrians, the sun over Delft at the drive's time, which the
// backbone works out from each frame's stamp), lineloc-backbone and lineloc-robot as separate
// processes over DDS on loopback in real time, and the robot's poses checked
// against the simulator's ground truth — once as it is, once with the
// backbone killed mid-drive and started again, once with a second robot on
// another drive served by the same backbone.
//
// Bounds, from the simulated noise: the renderer's sensor noise and blur leave
// segment endpoints 0.05-0.3 px uncertain; twenty-odd building lines 10-60 m
// away at f = 536 px then place the camera within 1-2 cm (1 sigma) and 0.05
// degrees, and the inertial filter between fixes adds less. The issue's 5 cm
// position RMSE and 0.2 degree attitude RMSE after the first fix are about
// three of those sigmas. DGPS (4 m per axis) and compass (2 degrees) only
// start the filter: a fix must come, and once found the robot must be
// answered with a pose almost always. How soon the first fix comes depends on
// how fast the machine searches: it is printed, not asserted.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <thread>

#include "common/trajectory/tum_trajectory.h"
#include "tests/support/child_process.h"
#include "tests/support/delft_drive.h"
#include "tests/support/test_database.h"
#include "tests/support/test_dds.h"

namespace fs = std::filesystem;

namespace lineloc {
namespace {

constexpr int kDriveSeconds = 30;
constexpr double kMaxPositionRmseM = 0.05;
constexpr double kMaxAttitudeRmseDeg = 0.2;
constexpr double kMinFixedFraction = 0.95;
// The first fix answers its frame after a search of one to two seconds, and
// the robot's predictions include it only once it has arrived: accuracy is
// checked from this long after the first fixed frame.
constexpr double kSettleSeconds = 3.0;
// The restart test: the backbone dies this long after the robot's first fix,
// stays away this long, and the drive's last seconds are checked.
constexpr int kKillAfterFirstFixSeconds = 3;
constexpr int kOutageSeconds = 3;
constexpr double kLastPartSeconds = 8.0;

// True once the TUM file at `path` holds a whole pose line (the robot writes
// and flushes one per fix).
bool holdsAPose(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != '#' && !in.eof()) {
      return true;
    }
  }
  return false;
}

std::map<int64_t, Eigen::Isometry3d> byStamp(const std::vector<StampedPose>& poses) {
  std::map<int64_t, Eigen::Isometry3d> result;
  for (const StampedPose& pose : poses) {
    result[pose.stamp_ns] = pose.pose;
  }
  return result;
}

std::string readFile(const fs::path& path) {
  std::ifstream stream(path);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

int countIn(const std::string& text, const std::string& pattern) {
  std::smatch match;
  return std::regex_search(text, match, std::regex(pattern)) ? std::stoi(match[1]) : -1;
}

void runOrFail(const std::string& program, std::vector<std::string> args, const fs::path& log,
               int timeout_ms) {
  test::ChildProcess process(std::string(LINELOC_BIN_DIR) + "/" + program, args, log.string());
  const std::optional<int> exit_code = process.wait(timeout_ms);
  ASSERT_EQ(exit_code, std::optional<int>(0)) << program << ":\n" << readFile(log);
}

// Position and attitude RMSE of the fused poses from `from_ns` on.
struct Accuracy {
  double position_rmse_m = 0.0;
  double attitude_rmse_deg = 0.0;
  int frames = 0;
};

Accuracy accuracyFrom(const std::map<int64_t, Eigen::Isometry3d>& fused,
                      const std::map<int64_t, Eigen::Isometry3d>& truth, int64_t from_ns) {
  double squared_position = 0.0;
  double squared_attitude = 0.0;
  Accuracy accuracy;
  for (auto pose = fused.lower_bound(from_ns); pose != fused.end(); ++pose) {
    const auto true_pose = truth.find(pose->first);
    if (true_pose == truth.end()) {
      ADD_FAILURE() << "no ground truth at " << pose->first;
      continue;
    }
    squared_position +=
        (pose->second.translation() - true_pose->second.translation()).squaredNorm();
    const double angle_rad =
        Eigen::AngleAxisd(pose->second.linear().transpose() * true_pose->second.linear()).angle();
    squared_attitude += angle_rad * angle_rad;
    ++accuracy.frames;
  }
  if (accuracy.frames > 0) {
    accuracy.position_rmse_m = std::sqrt(squared_position / accuracy.frames);
    accuracy.attitude_rmse_deg = std::sqrt(squared_attitude / accuracy.frames) * 180.0 / M_PI;
  }
  return accuracy;
}

class DelftDrive : public ::testing::Test {
 protected:
  void SetUp() override {
    work_ = fs::temp_directory_path() / ("delft_drive_" + std::to_string(getpid()));
    fs::remove_all(work_);
    fs::create_directories(work_);
    const fs::path city = test::delftCityModel();
    ASSERT_TRUE(fs::exists(city)) << "shared data missing: " << city;
    std::vector<std::string> load = {"--db", database_.conninfo(), "--site", "delft", "--origin"};
    load.insert(load.end(), origin_.begin(), origin_.end());
    load.push_back(city.string());
    runOrFail("lineloc-load", load, work_ / "load.log", 120'000);
    simulateDrive(1, "dataset");
  }
  void TearDown() override {
    if (!HasFailure()) {
      fs::remove_all(work_);
    }
  }

  // Simulates the drive of `seed` into `dataset`, under work_.
  void simulateDrive(int seed, const fs::path& dataset) const {
    std::vector<std::string> simulate = {"--city-model",
                                         test::delftCityModel().string(),
                                         "--output",
                                         (work_ / dataset).string(),
                                         "--seed",
                                         std::to_string(seed),
                                         "--duration-s",
                                         std::to_string(kDriveSeconds),
                                         "--camera-height-m",
                                         fmt::format("{}", test::kDelftCameraHeightM),
                                         "--start-utc",
                                         test::kDelftDriveStartUtc,
                                         "--sun-from-clock",
                                         "--site-origin"};
    simulate.insert(simulate.end(), origin_.begin(), origin_.end());
    runOrFail("lineloc-sim", simulate, work_ / (dataset.string() + "-sim.log"), 600'000);
  }

  std::vector<std::string> dds() const {
    return {"--domain-id", std::to_string(test::testDomainId()), "--dds-config",
            test::testDdsConfig()};
  }

  std::unique_ptr<test::ChildProcess> startBackbone(const std::string& log_name) const {
    std::vector<std::string> args = dds();
    const DriveSimulationConfig simulated;
    args.insert(args.end(), {"--db", database_.conninfo(), "--site", "delft", "--sun-from-clock",
                             "--ambient", fmt::format("{}", simulated.ambient)});
    return std::make_unique<test::ChildProcess>(std::string(LINELOC_BIN_DIR) + "/lineloc-backbone",
                                                args, (work_ / log_name).string());
  }

  // Robot `robot_id` driving through `dataset`; it writes <robot_id>.log,
  // <robot_id>-fixes.tum and <robot_id>-fused.tum under work_.
  std::unique_ptr<test::ChildProcess> startRobot(const std::string& robot_id = "drive",
                                                 const fs::path& dataset = "dataset") const {
    std::vector<std::string> args = dds();
    args.insert(
        args.end(),
        {"--robot-id", robot_id, "--images", (work_ / dataset).string(), "--calibration",
         (work_ / dataset / "cam0" / "calibration.yaml").string(), "--site-crs", "EPSG:7415",
         "--camera-height-m", fmt::format("{}", test::kDelftCameraHeightM), "--trajectory-out",
         (work_ / (robot_id + "-fixes.tum")).string(), "--fused-trajectory-out",
         (work_ / (robot_id + "-fused.tum")).string(), "--site-origin"});
    args.insert(args.end(), origin_.begin(), origin_.end());
    return std::make_unique<test::ChildProcess>(std::string(LINELOC_BIN_DIR) + "/lineloc-robot",
                                                args, (work_ / (robot_id + ".log")).string());
  }

  void waitForRobot(test::ChildProcess& robot, const std::string& robot_id = "drive") const {
    ASSERT_EQ(robot.wait((kDriveSeconds + 120) * 1000), std::optional<int>(0))
        << readFile(work_ / (robot_id + ".log"));
  }

  // Robot `robot_id`'s drive through `dataset`, once it has ended: one answer
  // per frame sent, and from kSettleSeconds after its first fix, position and
  // attitude within the bounds above and a fix on nearly every frame.
  void expectLocalized(const std::string& robot_id = "drive",
                       const fs::path& dataset = "dataset") const {
    const std::string robot_log = readFile(work_ / (robot_id + ".log"));
    const int sent = countIn(robot_log, R"(([0-9]+) frames sent)");
    ASSERT_GT(sent, kDriveSeconds * 10) << robot_log;
    EXPECT_EQ(countIn(robot_log, R"(([0-9]+) fixes received)"), sent) << robot_log;
    const auto fused = poses(robot_id + "-fused.tum");
    const auto fixes = poses(robot_id + "-fixes.tum");
    ASSERT_FALSE(fixes.empty()) << robot_log;
    ASSERT_FALSE(fused.empty());
    const int64_t first_frame_ns = fused.begin()->first;
    const int64_t first_fix_ns = fixes.begin()->first;

    const Accuracy accuracy =
        accuracyFrom(fused, poses(dataset / "groundtruth_cam0.tum"),
                     first_fix_ns + static_cast<int64_t>(kSettleSeconds * 1e9));
    const auto fixes_after =
        static_cast<double>(std::distance(fixes.lower_bound(first_fix_ns), fixes.end()));
    const auto frames_after =
        static_cast<double>(std::distance(fused.lower_bound(first_fix_ns), fused.end()));
    fmt::print(
        "{}: first fix {:.2f} s after the first frame; from {:.0f} s after it, position "
        "RMSE {:.3f} m, attitude RMSE {:.3f} deg over {} frames; {} fixes over {} frames\n",
        robot_id, (first_fix_ns - first_frame_ns) * 1e-9, kSettleSeconds, accuracy.position_rmse_m,
        accuracy.attitude_rmse_deg, accuracy.frames, fixes_after, frames_after);
    ASSERT_GT(accuracy.frames, 0);
    EXPECT_LE(accuracy.position_rmse_m, kMaxPositionRmseM) << robot_id;
    EXPECT_LE(accuracy.attitude_rmse_deg, kMaxAttitudeRmseDeg) << robot_id;
    EXPECT_GE(fixes_after / frames_after, kMinFixedFraction) << robot_id;
  }

  std::map<int64_t, Eigen::Isometry3d> poses(const fs::path& relative) const {
    return byStamp(readTumFile((work_ / relative).string()));
  }

  fs::path work_;
  const std::vector<std::string> origin_ = test::delftSiteOriginArgs();
  test::TestDatabase database_{"delft_drive"};
};

TEST_F(DelftDrive, TheRobotKnowsItsPoseToCentimetresSoonAfterADgpsStart) {
  const auto backbone = startBackbone("backbone.log");
  const auto robot = startRobot();
  waitForRobot(*robot);
  backbone->signal(SIGTERM);
  backbone->wait(10'000);
  expectLocalized();
  // Tracked frames take the hidden-line removal their exposure notice started,
  // unless the notice came after its LineSet (skipped and counted) or a
  // search ended between the two and changed the prior. How many come late
  // depends on the machine's load, which wakes the notices' thread late:
  // beside other tests (ctest -j2 on two cores), 518 of 549 tracked frames
  // took theirs and 35 notices came late. Most must take theirs, and nine in
  // ten must take theirs or have come late.
  const std::string backbone_log = readFile(work_ / "backbone.log");
  const int with_a_pose = countIn(backbone_log, R"(\(([0-9]+) with a pose)");
  const int tracked =
      with_a_pose - countIn(backbone_log, R"(([0-9]+) searched from a poor prediction)");
  const int ahead =
      countIn(backbone_log, R"(([0-9]+) tracked with the hidden lines removed at exposure)");
  const int late = countIn(backbone_log, R"(([0-9]+) exposure notices skipped)");
  fmt::print(
      "{} of {} tracked frames took their exposure notice's hidden-line removal, {} notices came "
      "after their LineSet\n",
      ahead, tracked, late);
  EXPECT_GE(ahead, 0.5 * tracked) << backbone_log;
  EXPECT_GE(ahead + late, 0.9 * tracked) << backbone_log;
}

// One backbone serves a second robot on another drive (seed 8) at the same
// time: each robot's searches, tracking and fixes are its own, and both know
// their pose as the one robot alone does.
TEST_F(DelftDrive, OneBackboneLocalizesTwoRobotsAtOnce) {
  simulateDrive(8, "dataset-2");
  const auto backbone = startBackbone("backbone.log");
  const auto first = startRobot();
  const auto second = startRobot("drive-2", "dataset-2");
  waitForRobot(*first);
  waitForRobot(*second, "drive-2");
  backbone->signal(SIGTERM);
  backbone->wait(10'000);
  expectLocalized();
  expectLocalized("drive-2", "dataset-2");
}

// The backbone killed mid-drive and started again: the robot dead-reckons
// through the outage, the new backbone (which knows nothing of the robot)
// finds it again, and the end of the drive is as accurate as ever.
TEST_F(DelftDrive, ABackboneKilledMidDriveAndRestartedPullsTheRobotBack) {
  auto backbone = startBackbone("backbone.log");
  const auto robot = startRobot();
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(kDriveSeconds);
  while (!holdsAPose(work_ / "drive-fixes.tum")) {
    ASSERT_LT(std::chrono::steady_clock::now(), give_up) << "no fix before the kill:\n"
                                                         << readFile(work_ / "drive.log");
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::this_thread::sleep_for(std::chrono::seconds(kKillAfterFirstFixSeconds));
  backbone->signal(SIGKILL);
  backbone->wait(10'000);
  std::this_thread::sleep_for(std::chrono::seconds(kOutageSeconds));
  backbone = startBackbone("backbone-restarted.log");
  waitForRobot(*robot);
  backbone->signal(SIGTERM);
  backbone->wait(10'000);

  const auto fused = poses("drive-fused.tum");
  const auto fixes = poses("drive-fixes.tum");
  ASSERT_FALSE(fused.empty());
  // The outage shows as frames without a fix (the robot dead-reckoned).
  int64_t longest_gap_ns = 0;
  for (auto fix = fixes.begin(); fix != fixes.end() && std::next(fix) != fixes.end(); ++fix) {
    longest_gap_ns = std::max(longest_gap_ns, std::next(fix)->first - fix->first);
  }
  EXPECT_GE(longest_gap_ns * 1e-9, kOutageSeconds - 1.0);
  const int64_t end_ns = fused.rbegin()->first;
  const int64_t last_part_ns = end_ns - static_cast<int64_t>(kLastPartSeconds * 1e9);
  ASSERT_NE(fixes.lower_bound(last_part_ns), fixes.end()) << "no fix after the restart:\n"
                                                          << readFile(work_ / "drive.log");
  const Accuracy accuracy =
      accuracyFrom(fused, poses(fs::path("dataset") / "groundtruth_cam0.tum"), last_part_ns);
  fmt::print(
      "restart: last {:.0f} s of the drive, position RMSE {:.3f} m, attitude RMSE {:.3f} "
      "deg over {} frames\n",
      kLastPartSeconds, accuracy.position_rmse_m, accuracy.attitude_rmse_deg, accuracy.frames);
  EXPECT_LE(accuracy.position_rmse_m, kMaxPositionRmseM);
  EXPECT_LE(accuracy.attitude_rmse_deg, kMaxAttitudeRmseDeg);
}

}  // namespace
}  // namespace lineloc
