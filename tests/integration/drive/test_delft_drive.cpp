// The README's main job, shortened, on the bundled Delft tile (city_drive.h):
// a 30 s drive as it is, once with the backbone killed mid-drive and started
// again, once through faults (a lossy network, the database stopped, the
// backbone paused), once with a second robot on another drive served by the
// same backbone.
#include <cstdlib>

#include "tests/integration/drive/city_drive.h"
#include "tests/support/delft_drive.h"

namespace lineloc {
namespace {

using namespace lineloc::test;

class DelftDrive : public CityDrive {
 protected:
  DelftDrive()
      : CityDrive({"delft", delftCityModel(), delftSiteOriginArgs(), kDelftCameraHeightM,
                   kDelftDriveStartUtc}) {}

  void SetUp() override {
    CityDrive::SetUp();
    simulateDrive(1, "dataset");
  }
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
  ASSERT_TRUE(waitForAFix(std::chrono::seconds(kDriveSeconds))) << "no fix before the kill:\n"
                                                                << readFile(work_ / "drive.log");
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
  EXPECT_GE(longestGapS(fixes), kOutageSeconds - 1.0);
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

// The private PostGIS cluster of the tests: deploy/pg.sh `command` ("stop", "start").
void runPgScript(const std::string& command, const fs::path& log) {
  const char* port = std::getenv("LINELOC_TEST_PG_PORT");
  ASSERT_NE(port, nullptr);
  setenv("LINELOC_PG_PORT", port, 1);
  ChildProcess script(std::string(LINELOC_SOURCE_DIR) + "/deploy/pg.sh", {command}, log.string());
  ASSERT_EQ(script.wait(60'000), std::optional<int>(0)) << readFile(log);
}

// Faults in turn over a network that loses one packet in ten and delays the
// others by up to 50 ms, out of order: the database
// stopped for 5 s and started again, then the backbone paused (SIGSTOP) for
// 3 s, after which it answers the frames the network held for it late. The
// robot dead-reckons through each, is fixed again after each, is never sure
// of a wrong pose, and ends the drive as accurate as ever.
TEST_F(DelftDrive, ThroughALossyJitteryNetworkADatabaseOutageAndAPausedBackboneTheRobotStaysRight) {
  constexpr int kDatabaseOutageSeconds = 5;
  constexpr int kPauseSeconds = 3;
  degradeNetwork(100, 50);
  auto backbone = startBackbone("backbone.log");
  const auto robot = startRobot();
  ASSERT_TRUE(waitForAFix(std::chrono::seconds(kDriveSeconds))) << readFile(work_ / "drive.log");
  std::this_thread::sleep_for(std::chrono::seconds(2));
  runPgScript("stop", work_ / "pg-stop.log");
  std::this_thread::sleep_for(std::chrono::seconds(kDatabaseOutageSeconds));
  runPgScript("start", work_ / "pg-start.log");
  std::this_thread::sleep_for(std::chrono::seconds(2));
  backbone->signal(SIGSTOP);
  std::this_thread::sleep_for(std::chrono::seconds(kPauseSeconds));
  backbone->signal(SIGCONT);
  waitForRobot(*robot);
  backbone->signal(SIGTERM);
  EXPECT_EQ(backbone->wait(10'000), std::optional<int>(0)) << readFile(work_ / "backbone.log");

  const std::string report = consistencyReport("drive", "dataset");
  EXPECT_EQ(fixesBeyondThreeSigma(report), 0) << report;
  EXPECT_EQ(statesBeyondThreeSigma(report), 0) << report;
  const auto fixes = poses("drive-fixes.tum");
  const auto fused = poses("drive-fused.tum");
  ASSERT_FALSE(fused.empty());
  // The drive's last kLastPartSeconds come after the pause.
  const int64_t last_part_ns = fused.rbegin()->first - static_cast<int64_t>(kLastPartSeconds * 1e9);
  EXPECT_GT(std::distance(fixes.lower_bound(last_part_ns), fixes.end()), 10)
      << "too few fixes after the faults:\n"
      << readFile(work_ / "drive.log");
  const Accuracy accuracy =
      accuracyFrom(fused, poses(fs::path("dataset") / "groundtruth_cam0.tum"), last_part_ns);
  const std::string robot_log = readFile(work_ / "drive.log");
  const size_t latency = robot_log.find("exposure -> fix");
  fmt::print("faults: last {:.0f} s, position RMSE {:.3f} m, attitude RMSE {:.3f} deg; {}\n",
             kLastPartSeconds, accuracy.position_rmse_m, accuracy.attitude_rmse_deg,
             latency == std::string::npos
                 ? std::string()
                 : robot_log.substr(latency, robot_log.find('\n', latency) - latency));
  EXPECT_LE(accuracy.position_rmse_m, kMaxPositionRmseM);
  EXPECT_LE(accuracy.attitude_rmse_deg, kMaxAttitudeRmseDeg);
}

}  // namespace
}  // namespace lineloc
