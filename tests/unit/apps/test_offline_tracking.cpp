// lineloc-track's pipeline on a simulated drive through the bundled Delft
// model, rendered by the realistic camera: started at the first frame's true
// pose, it must follow the camera, and malformed options must be refused
// naming the option. The drive (seed 4) starts moving along the street with
// façades in view all through; a view of one wall and the open end of the
// street (other seeds) has too few model lines to align, which the tracker
// rightly reports.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <sstream>

#include "apps/offline_tracking.h"
#include "common/trajectory/fix_log.h"
#include "common/trajectory/tum_trajectory.h"
#include "tests/support/delft_drive.h"
#include "tests/support/pose_option.h"

namespace lineloc {
namespace {

namespace fs = std::filesystem;

class OfflineTracking : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = fs::temp_directory_path() / ("offline_tracking_" + std::to_string(getpid()));
    fs::remove_all(folder_);
    DriveSimulationConfig drive;
    drive.seed = 4;
    drive.duration_s = 2.0;
    drive.camera_rate_hz = 10.0;
    drive.drive.initial_still_s = 0.0;
    drive.drive.initial_speed_m_s = 1.0;
    frames_ = new test::SimulatedFrames(test::simulateDelftDrive(drive, folder_ / "dataset"));
    sunlight_ = drivingSunlight(drive);
  }
  static void TearDownTestSuite() {
    delete frames_;
    fs::remove_all(folder_);
  }

  // Tracking from the first frame's true pose, told the drive's sun.
  static OfflineTrackingConfig configFromTruth() {
    OfflineTrackingConfig config;
    config.drive.city_model = test::delftCityModel().string();
    const Eigen::Vector3d origin = test::delftSiteOrigin();
    config.drive.site_origin = {origin.x(), origin.y(), origin.z()};
    config.drive.images = (folder_ / "dataset" / "cam0").string();
    config.drive.camera_calibration = (folder_ / "dataset" / "cam0" / "calibration.yaml").string();
    const Eigen::Isometry3d& first = frames_->truth.front();
    config.predicted_pose = test::poseOptionValues(first);
    config.predicted_position_sigma_m = 0.05;
    config.predicted_rotation_sigma_deg = 0.5;
    config.drive.sun_deg = {sunlight_.azimuth_deg(), sunlight_.elevation_deg()};
    config.out = (folder_ / "poses.tum").string();
    return config;
  }

  static fs::path folder_;
  static test::SimulatedFrames* frames_;
  static Sunlight sunlight_;
};

fs::path OfflineTracking::folder_;
test::SimulatedFrames* OfflineTracking::frames_ = nullptr;
Sunlight OfflineTracking::sunlight_;

TEST_F(OfflineTracking, FollowsTheCameraThroughADrive) {
  std::ostringstream out;
  const OfflineTrackingSummary summary = runOfflineTracking(configFromTruth(), out);
  ASSERT_EQ(summary.frames, static_cast<int>(frames_->images.size()));
  EXPECT_GE(summary.aligned, summary.frames * 9 / 10) << out.str();
  std::map<int64_t, Eigen::Isometry3d> truth;
  for (size_t i = 0; i < frames_->stamps_ns.size(); ++i) {
    truth[frames_->stamps_ns[i]] = frames_->truth[i];
  }
  std::vector<double> errors_m;
  for (const StampedPose& pose : readTumFile((folder_ / "poses.tum").string())) {
    errors_m.push_back((pose.pose.translation() - truth.at(pose.stamp_ns).translation()).norm());
  }
  ASSERT_EQ(errors_m.size(), frames_->images.size());
  std::sort(errors_m.begin(), errors_m.end());
  // Tracking's position error is centimetres (docs/evaluation.md); a pose in
  // another basin is metres off.
  EXPECT_LT(errors_m[errors_m.size() / 2], 0.05);
  EXPECT_LT(errors_m.back(), 0.25);
  EXPECT_NE(out.str().find(fmt::format("{} frames, {} aligned", summary.frames, summary.aligned)),
            std::string::npos)
      << out.str();
}

TEST_F(OfflineTracking, LogsEachFrameAsTheRobotLogsAFix) {
  OfflineTrackingConfig config = configFromTruth();
  config.fix_log_out = (folder_ / "fixes.txt").string();
  std::ostringstream out;
  const OfflineTrackingSummary summary = runOfflineTracking(config, out);
  const std::vector<LoggedFix> fixes = readFixLog(config.fix_log_out);
  const std::vector<StampedPose> poses = readTumFile(config.out);
  ASSERT_EQ(fixes.size(), poses.size());
  int ok = 0;
  for (size_t i = 0; i < fixes.size(); ++i) {
    EXPECT_EQ(fixes[i].stamp_ns, frames_->stamps_ns[i]);
    EXPECT_LT((fixes[i].T_world_camera.pose.translation() - poses[i].pose.translation()).norm(),
              1e-6);
    if (fixes[i].status == "ok") {
      ++ok;
      EXPECT_GE(fixes[i].inliers, 6u);
      EXPECT_GT(fixes[i].model_lines, 0u);
      // An OK answer's covariance is a covariance, and it covers the truth
      // as the robot's fixes must (chi^2_6 at 0.9973).
      EXPECT_GT(fixes[i].T_world_camera.covariance.determinant(), 0.0);
      EXPECT_LT(normalizedErrorSquared(fixes[i].T_world_camera, frames_->truth[i]), 20.06);
    }
  }
  EXPECT_EQ(ok, summary.aligned);
}

TEST_F(OfflineTracking, RefusesAPredictedPoseThatIsNoPose) {
  OfflineTrackingConfig config = configFromTruth();
  config.predicted_pose = {1.0, 2.0, 1.5, 0.0, 0.0, 0.0};
  std::ostringstream out;
  try {
    runOfflineTracking(config, out);
    FAIL() << "six numbers accepted as a pose";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("predicted_pose"), std::string::npos) << error.what();
  }
  config.predicted_pose = {1.0, 2.0, 1.5, 0.0, 0.0, 0.0, 0.0};
  EXPECT_THROW(runOfflineTracking(config, out), std::invalid_argument);
}

TEST_F(OfflineTracking, NamesAnImageFolderThatIsMissing) {
  OfflineTrackingConfig config = configFromTruth();
  config.drive.images = (folder_ / "no_such_folder").string();
  std::ostringstream out;
  try {
    runOfflineTracking(config, out);
    FAIL() << "a missing image folder accepted";
  } catch (const std::exception& error) {
    EXPECT_NE(std::string(error.what()).find("no_such_folder"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace lineloc
