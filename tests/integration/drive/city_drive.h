// A simulated drive through a city model, end to end: the model loaded into a
// real PostGIS database, a drive simulated through it (DGPS + compass start,
// parked cars, trees, pedestrians, the sun at the drive's time, which the
// backbone works out from each frame's stamp), lineloc-backbone and
// lineloc-robot as separate processes over DDS on loopback in real time, and
// the robot's poses checked against the simulator's ground truth.
//
// Bounds, from the simulated noise: the camera's noise and blur leave
// segment endpoints 0.05-0.3 px uncertain; twenty-odd building lines 10-60 m
// away at f = 536 px then place the camera within 1-2 cm (1 sigma) and 0.05
// degrees, and the inertial filter between fixes adds less. A position RMSE
// of 5 cm and an attitude RMSE of 0.2 degree after the first fix are about
// three of those sigmas. DGPS (4 m per axis) and compass (2 degrees) only
// start the filter: a fix must come, and once found the robot must be
// answered with a pose almost always. How soon the first fix comes depends on
// how fast the machine searches: it is printed, not asserted.
#pragma once

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
#include <optional>
#include <regex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "common/trajectory/tum_trajectory.h"
#include "sim/dataset/drive_simulation.h"
#include "tests/support/child_process.h"
#include "tests/support/test_database.h"
#include "tests/support/test_dds.h"

namespace lineloc::test {

namespace fs = std::filesystem;

inline constexpr int kDriveSeconds = 30;
inline constexpr double kMaxPositionRmseM = 0.05;
inline constexpr double kMaxAttitudeRmseDeg = 0.2;
inline constexpr double kMinFixedFraction = 0.95;
// The share of a consistent estimator's estimates beyond chi2_6(0.9973).
inline constexpr double kConsistentShareBeyond = 0.0027;
// The first fix answers its frame after a search of one to two seconds, and
// the robot's predictions include it only once it has arrived: accuracy is
// checked from this long after the first fixed frame.
inline constexpr double kSettleSeconds = 3.0;
// The restart test: the backbone dies this long after the robot's first fix,
// stays away this long, and the drive's last seconds are checked.
inline constexpr int kKillAfterFirstFixSeconds = 3;
inline constexpr int kOutageSeconds = 3;
inline constexpr double kLastPartSeconds = 8.0;

// True once the TUM file at `path` holds a whole pose line (the robot writes
// and flushes one per fix).
inline bool holdsAPose(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != '#' && !in.eof()) {
      return true;
    }
  }
  return false;
}

inline std::map<int64_t, Eigen::Isometry3d> byStamp(const std::vector<StampedPose>& poses) {
  std::map<int64_t, Eigen::Isometry3d> result;
  for (const StampedPose& pose : poses) {
    result[pose.stamp_ns] = pose.pose;
  }
  return result;
}

// The longest time between consecutive poses (s).
inline double longestGapS(const std::map<int64_t, Eigen::Isometry3d>& poses) {
  int64_t longest_ns = 0;
  for (auto pose = poses.begin(); pose != poses.end() && std::next(pose) != poses.end(); ++pose) {
    longest_ns = std::max(longest_ns, std::next(pose)->first - pose->first);
  }
  return longest_ns * 1e-9;
}

inline std::string readFile(const fs::path& path) {
  std::ifstream stream(path);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

inline int countIn(const std::string& text, const std::string& pattern) {
  std::smatch match;
  return std::regex_search(text, match, std::regex(pattern)) ? std::stoi(match[1]) : -1;
}

inline void runOrFail(const std::string& program, std::vector<std::string> args,
                      const fs::path& log, int timeout_ms) {
  ChildProcess process(std::string(LINELOC_BIN_DIR) + "/" + program, args, log.string());
  const std::optional<int> exit_code = process.wait(timeout_ms);
  ASSERT_EQ(exit_code, std::optional<int>(0)) << program << ":\n" << readFile(log);
}

// Position and attitude RMSE of the fused poses from `from_ns` on.
struct Accuracy {
  double position_rmse_m = 0.0;
  double attitude_rmse_deg = 0.0;
  int frames = 0;
};

inline Accuracy accuracyFrom(const std::map<int64_t, Eigen::Isometry3d>& fused,
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

// What a drive needs of its city: the model, the site it loads into, the
// site origin (model CRS, as command-line words), the camera's height and
// when the drive starts (UTC), which places the sun.
struct DriveCity {
  std::string site;
  fs::path model;
  std::vector<std::string> origin;
  double camera_height_m = 1.5;
  std::string start_utc;
};

class CityDrive : public ::testing::Test {
 protected:
  explicit CityDrive(DriveCity city) : city_(std::move(city)) {}

  void SetUp() override {
    work_ = fs::temp_directory_path() / (city_.site + "_drive_" + std::to_string(getpid()));
    fs::remove_all(work_);
    fs::create_directories(work_);
    ASSERT_TRUE(fs::exists(city_.model)) << "city model missing: " << city_.model;
    std::vector<std::string> load = {"--db", database_.conninfo(test::DatabaseRole::kWriter),
                                     "--site", city_.site, "--site-origin"};
    load.insert(load.end(), city_.origin.begin(), city_.origin.end());
    load.push_back(city_.model.string());
    runOrFail("lineloc-load", load, work_ / "load.log", 120'000);
  }
  void TearDown() override {
    if (!HasFailure()) {
      fs::remove_all(work_);
    }
  }

  // Simulates the `duration_s` drive of `seed` into `dataset`, under work_,
  // with lineloc-sim's `options` besides.
  void simulateDrive(int seed, const fs::path& dataset,
                     const std::vector<std::string>& options = {},
                     int duration_s = kDriveSeconds) const {
    std::vector<std::string> simulate = {"--city-model",
                                         city_.model.string(),
                                         "--out",
                                         (work_ / dataset).string(),
                                         "--seed",
                                         std::to_string(seed),
                                         "--duration-s",
                                         std::to_string(duration_s),
                                         "--camera-height-m",
                                         fmt::format("{}", city_.camera_height_m),
                                         "--start-utc",
                                         city_.start_utc,
                                         "--sun-from-clock",
                                         "--site-origin"};
    simulate.insert(simulate.end(), city_.origin.begin(), city_.origin.end());
    simulate.insert(simulate.end(), options.begin(), options.end());
    runOrFail("lineloc-sim", simulate, work_ / (dataset.string() + "-sim.log"), 600'000);
  }

  // The DDS options of a participant secured with an identity of its own
  // (deploy/dds-security.sh), as a deployment runs it: `kind` "robot" or
  // "backbone", `name` its id.
  std::vector<std::string> dds(const std::string& kind, const std::string& name) const {
    const std::string overlay = issueDdsIdentity((work_ / "pki").string(), kind, name);
    return {"--domain-id", std::to_string(testDomainId()), "--dds-config",
            testDdsConfig() + extra_dds_config_ + "," + overlay};
  }

  // From now on the backbones and robots started lose `lost_per_mille` of the
  // packets they send (Cyclone DDS's transmit lossiness, a test setting;
  // reliable topics resend what was lost) and send each of the others up to
  // `jitter_ms` late (tests/support/network_jitter), out of order.
  void degradeNetwork(int lost_per_mille, int jitter_ms) {
    const fs::path overlay = work_ / "lossy.xml";
    std::ofstream(overlay) << "<CycloneDDS xmlns=\"https://cdds.io/config\"><Domain id=\"any\">"
                              "<Internal><Test><XmitLossiness>"
                           << lost_per_mille
                           << "</XmitLossiness></Test></Internal></Domain></CycloneDDS>\n";
    extra_dds_config_ = ",";
    extra_dds_config_ += overlay.string();
    environment_ = networkJitterEnvironment(jitter_ms);
  }

  // Waits until robot `robot_id` has had an OK fix; false after `timeout`.
  bool waitForAFix(std::chrono::seconds timeout, const std::string& robot_id = "drive") const {
    const auto give_up = std::chrono::steady_clock::now() + timeout;
    while (!holdsAPose(work_ / (robot_id + "-fixes.tum"))) {
      if (std::chrono::steady_clock::now() > give_up) {
        return false;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return true;
  }

  // Backbone `name`, with lineloc-backbone's `options` besides.
  std::unique_ptr<ChildProcess> startBackbone(const std::string& log_name,
                                              const std::string& name = "test",
                                              const std::vector<std::string>& options = {}) const {
    std::vector<std::string> args = dds("backbone", name);
    args.insert(args.end(), options.begin(), options.end());
    const DriveSimulationConfig simulated;
    args.insert(args.end(),
                {"--db", database_.conninfo(test::DatabaseRole::kReader), "--site", city_.site,
                 "--sun-from-clock", "--ambient", fmt::format("{}", simulated.ambient)});
    return std::make_unique<ChildProcess>(std::string(LINELOC_BIN_DIR) + "/lineloc-backbone", args,
                                          (work_ / log_name).string(), environment_);
  }

  // Robot `robot_id` driving through `dataset`, with lineloc-robot's
  // `options` besides; it writes <robot_id>.log, <robot_id>-fixes.tum and
  // <robot_id>-fused.tum under work_.
  std::unique_ptr<ChildProcess> startRobot(const std::string& robot_id = "drive",
                                           const fs::path& dataset = "dataset",
                                           const std::vector<std::string>& options = {}) const {
    std::vector<std::string> args = robotArgs(robot_id, dataset, options);
    args.insert(args.end(), {"--images", (work_ / dataset).string()});
    return std::make_unique<ChildProcess>(std::string(LINELOC_BIN_DIR) + "/lineloc-robot", args,
                                          (work_ / (robot_id + ".log")).string(), environment_);
  }

  // lineloc-robot's arguments for robot `robot_id` with the camera of
  // `dataset`, its outputs under work_ (<robot_id>-fixes.tum ...), and
  // `options`; without its input.
  std::vector<std::string> robotArgs(const std::string& robot_id, const fs::path& dataset,
                                     const std::vector<std::string>& options) const {
    std::vector<std::string> args = dds("robot", robot_id);
    args.insert(args.end(), options.begin(), options.end());
    args.insert(args.end(),
                {"--robot-id", robot_id, "--camera-calibration",
                 (work_ / dataset / "cam0" / "calibration.yaml").string(), "--site-crs",
                 "EPSG:7415", "--camera-height-m", fmt::format("{}", city_.camera_height_m),
                 "--trajectory-out", (work_ / (robot_id + "-fixes.tum")).string(),
                 "--fused-trajectory-out", (work_ / (robot_id + "-fused.tum")).string(),
                 "--fix-log-out", (work_ / (robot_id + "-fixes.txt")).string(), "--state-log-out",
                 (work_ / (robot_id + "-states.txt")).string(), "--site-origin"});
    args.insert(args.end(), city_.origin.begin(), city_.origin.end());
    return args;
  }

  void waitForRobot(ChildProcess& robot, const std::string& robot_id = "drive",
                    int duration_s = kDriveSeconds) const {
    ASSERT_EQ(robot.wait((duration_s + 120) * 1000), std::optional<int>(0))
        << readFile(work_ / (robot_id + ".log"));
  }

  // Robot `robot_id`'s drive through `dataset`, once it has ended: one answer
  // per frame sent, a fix on nearly every frame from the first fix on, and at
  // most `max_share_beyond` of its OK fixes precise wrong poses (none by
  // default); returns the accuracy from kSettleSeconds after the first fix.
  Accuracy expectFoundAndAnswered(const std::string& robot_id = "drive",
                                  const fs::path& dataset = "dataset",
                                  double max_share_beyond = 0.0) const {
    const std::string robot_log = readFile(work_ / (robot_id + ".log"));
    const int sent = countIn(robot_log, R"(([0-9]+) frames sent)");
    EXPECT_GT(sent, kDriveSeconds * 10) << robot_log;
    EXPECT_EQ(countIn(robot_log, R"(([0-9]+) fixes received)"), sent) << robot_log;
    const auto fused = poses(robot_id + "-fused.tum");
    const auto fixes = poses(robot_id + "-fixes.tum");
    if (fixes.empty() || fused.empty()) {
      ADD_FAILURE() << "no fix:\n" << robot_log;
      return {};
    }
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
    EXPECT_GT(accuracy.frames, 0);
    EXPECT_GE(fixes_after / frames_after, kMinFixedFraction) << robot_id;
    const std::string report = consistencyReport(robot_id, dataset);
    EXPECT_LE(fixesBeyondThreeSigma(report), max_share_beyond * fixesWithGroundTruth(report))
        << report;
    return accuracy;
  }

  // The same, no reported state the robot was sure of and wrong in, and
  // position and attitude within the bounds above.
  void expectLocalized(const std::string& robot_id = "drive",
                       const fs::path& dataset = "dataset") const {
    const Accuracy accuracy = expectFoundAndAnswered(robot_id, dataset);
    const std::string report = consistencyReport(robot_id, dataset);
    EXPECT_EQ(statesBeyondThreeSigma(report), 0) << report;
    EXPECT_LE(accuracy.position_rmse_m, kMaxPositionRmseM) << robot_id;
    EXPECT_LE(accuracy.attitude_rmse_deg, kMaxAttitudeRmseDeg) << robot_id;
  }

  // lineloc-eval's report on robot `robot_id`'s drive through `dataset`:
  // each OK fix's and each reported state's error in its own covariance; of
  // those stamped within `window` (from, to, ns) when given.
  std::string consistencyReport(const std::string& robot_id, const fs::path& dataset,
                                std::optional<std::pair<int64_t, int64_t>> window = {}) const {
    const fs::path report = work_ / (robot_id + "-eval.log");
    fs::path fix_log = work_ / (robot_id + "-fixes.txt");
    fs::path state_log = work_ / (robot_id + "-states.txt");
    if (window) {
      fix_log = copyLinesWithin(fix_log, *window);
      state_log = copyLinesWithin(state_log, *window);
    }
    runOrFail("lineloc-eval",
              {"--ground-truth", (work_ / dataset / "groundtruth_cam0.tum").string(), "--estimate",
               (work_ / (robot_id + "-fused.tum")).string(), "--fix-log", fix_log.string(),
               "--state-log", state_log.string()},
              report, 60'000);
    return readFile(report);
  }

  // The header and the lines stamped within `window` of the log at `path`
  // (its first column: seconds), written beside it; returns the copy's path.
  static fs::path copyLinesWithin(const fs::path& path, std::pair<int64_t, int64_t> window) {
    fs::path copy = path;
    copy.replace_extension(".window.txt");
    std::ifstream in(path);
    std::ofstream out(copy);
    std::string line;
    while (std::getline(in, line)) {
      const bool header = !line.empty() && line[0] == '#';
      const auto stamp_ns = header ? 0 : static_cast<int64_t>(std::llround(std::stod(line) * 1e9));
      if (header || (stamp_ns >= window.first && stamp_ns <= window.second)) {
        out << line << '\n';
      }
    }
    return copy;
  }

  // OK fixes beyond chi2_6(0.9973) of their own covariance (precise wrong
  // poses), and states the robot reported from its first fix on beyond it
  // (the robot sure of a wrong pose), as lineloc-eval counts them.
  static int fixesBeyondThreeSigma(const std::string& report) {
    return countIn(report, R"(fixes: [^\n]*; ([0-9]+) beyond)");
  }
  static int statesBeyondThreeSigma(const std::string& report) {
    return countIn(report, R"(robot states: [^\n]*; ([0-9]+) beyond)");
  }
  static int fixesWithGroundTruth(const std::string& report) {
    return countIn(report, R"(fixes: [^\n]*% of ([0-9]+) with ground truth)");
  }

  // From the report: how long after the robot first moved its first OK fix
  // came (s; negative: before); NaN when the report does not say.
  static double firstFixAfterMovingS(const std::string& report) {
    std::smatch match;
    return std::regex_search(report, match,
                             std::regex(R"(first OK fix was received (-?[0-9.]+) s after that)"))
               ? std::stod(match[1])
               : std::nan("");
  }

  std::map<int64_t, Eigen::Isometry3d> poses(const fs::path& relative) const {
    return byStamp(readTumFile((work_ / relative).string()));
  }

  DriveCity city_;
  fs::path work_;
  TestDatabase database_{"city_drive"};
  std::string extra_dds_config_;
  std::vector<std::string> environment_;
};

}  // namespace lineloc::test
