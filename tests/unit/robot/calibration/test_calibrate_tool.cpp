#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>

#include "common/camera/camera_calibration.h"
#include "robot/calibration/calibrate_tool.h"
#include "synthetic_views.h"

namespace lineloc {
namespace {

namespace fs = std::filesystem;

class CalibrateTool : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              ("calibrate_tool_" +
               std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    options_.fix_skew = true;
    options_.distortion_model = DistortionModel::kOpenCv5;
    synthetic_ = testing::makeSyntheticViews(5, options_, 0.1, 42);
    config_.fix_skew = true;
    config_.distortion = "opencv5";
    config_.image_size = "640x480";
    config_.out = path("camera.yml");
    config_.points.push_back(writePoints("model.txt", synthetic_.views.model_points));
    for (size_t view = 0; view < synthetic_.views.image_points.size(); ++view) {
      config_.points.push_back(
          writePoints("view" + std::to_string(view) + ".txt", synthetic_.views.image_points[view]));
    }
  }
  void TearDown() override { fs::remove_all(folder_); }

  std::string path(const std::string& name) const { return (folder_ / name).string(); }

  // Three pairs per line, as another tool might export them.
  std::string writePoints(const std::string& name, const std::vector<Eigen::Vector2d>& points) {
    std::ofstream stream(path(name));
    stream.precision(17);
    for (size_t i = 0; i < points.size(); ++i) {
      stream << points[i].x() << ' ' << points[i].y() << (i % 3 == 2 ? '\n' : ' ');
    }
    return path(name);
  }

  void expectErrorNaming(const CalibrateToolConfig& config, const std::string& expected_part) {
    std::ostringstream log;
    try {
      runCalibrateTool(config, log);
      FAIL() << "no error; log:\n" << log.str();
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(expected_part), std::string::npos) << error.what();
    }
    EXPECT_FALSE(fs::exists(config.out)) << "a file was written despite the error";
  }

  fs::path folder_;
  CalibrationOptions options_;
  testing::SyntheticViews synthetic_;
  CalibrateToolConfig config_;
};

TEST_F(CalibrateTool, CalibratesFromPointFilesAndWritesOpenCvLayout) {
  config_.report = path("residuals.png");
  std::ostringstream log;
  ASSERT_EQ(runCalibrateTool(config_, log), 0) << log.str();
  const CameraCalibration calibration = readCameraCalibration(config_.out);
  const PinholeCamera& truth = synthetic_.truth.calibration.camera;
  // 0.1 px noise over 5 views: the standard deviation of fx is ~0.3 px; 2 px is
  // far beyond 3 sigma (the statistics are tested in test_zhang_calibration).
  EXPECT_NEAR(calibration.camera.fx, truth.fx, 2.0);
  EXPECT_NEAR(calibration.camera.cy, truth.cy, 2.0);
  EXPECT_EQ(calibration.camera.skew, 0.0);
  EXPECT_EQ(calibration.camera.width, 640);

  cv::FileStorage storage(config_.out, cv::FileStorage::READ);
  cv::Mat extrinsics;
  cv::Mat per_view;
  cv::Mat std_dev;
  storage["extrinsic_parameters"] >> extrinsics;
  storage["per_view_reprojection_errors"] >> per_view;
  storage["camera_matrix_std_dev"] >> std_dev;
  EXPECT_EQ(extrinsics.rows, 5);
  EXPECT_EQ(extrinsics.cols, 6);
  EXPECT_EQ(per_view.total(), 5u);
  EXPECT_GT(std_dev.at<double>(0), 0.0);
  // rms ~ sigma sqrt(2 - p / n) with 0.1 px noise per coordinate.
  EXPECT_NEAR(static_cast<double>(storage["avg_reprojection_error"]), 0.1 * std::sqrt(2.0), 0.03);
  EXPECT_FALSE(cv::imread(config_.report).empty());
  EXPECT_NE(log.str().find("RMS reprojection error"), std::string::npos);
}

TEST_F(CalibrateTool, ChecksAnExistingCalibration) {
  writeCameraCalibration(path("truth.yml"), synthetic_.truth.calibration);
  config_.check = path("truth.yml");
  config_.out = path("not_written.yml");
  std::ostringstream log;
  ASSERT_EQ(runCalibrateTool(config_, log), 0) << log.str();
  EXPECT_NE(log.str().find("RMS reprojection error"), std::string::npos);
  EXPECT_FALSE(fs::exists(config_.out));
}

TEST_F(CalibrateTool, MismatchedPointCountNamesTheFile) {
  std::vector<Eigen::Vector2d> short_view = synthetic_.views.image_points[2];
  short_view.pop_back();
  config_.points[3] = writePoints("short.txt", short_view);
  expectErrorNaming(config_, "short.txt: 53 points, but the model");
}

TEST_F(CalibrateTool, NonFiniteNumberNamesTheFile) {
  std::ofstream(path("view1.txt"), std::ios::app) << "\n nan 3\n";
  expectErrorNaming(config_, "view1.txt");
}

TEST_F(CalibrateTool, FewerThanThreeViewsAreRefused) {
  config_.points.resize(3);
  expectErrorNaming(config_, "only 2 usable views");
}

TEST_F(CalibrateTool, BadOptionsAreNamed) {
  CalibrateToolConfig config = config_;
  config.distortion = "fisheye";
  expectErrorNaming(config, "--distortion 'fisheye'");
  config = config_;
  config.image_size = "640";
  expectErrorNaming(config, "--image-size '640'");
  config = config_;
  config.images = path("*.png");
  expectErrorNaming(config, "either --images");
}

TEST_F(CalibrateTool, UnreadableImageIsNamed) {
  std::ofstream(path("broken.jpg")) << "not a jpeg";
  config_.points.clear();
  config_.images = path("*.jpg");
  expectErrorNaming(config_, "broken.jpg");
}

TEST_F(CalibrateTool, ImageClaimingMorePixelsThanTheLimitIsNamed) {
  // A PNG header claiming 20000 x 20000 pixels, and nothing after it.
  std::ofstream(path("huge.png")) << std::string(
      "\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0N \0\0N \x08\0\0\0\0", 29);
  config_.points.clear();
  config_.images = path("huge.png");
  expectErrorNaming(config_, "huge.png': its PNG header claims 20000 x 20000");
}

TEST_F(CalibrateTool, NoBoardAnywhereIsAnError) {
  cv::imwrite(path("grey1.png"), cv::Mat(480, 640, CV_8UC1, cv::Scalar(128)));
  cv::imwrite(path("grey2.png"), cv::Mat(480, 640, CV_8UC1, cv::Scalar(30)));
  config_.points.clear();
  config_.images = path("grey*.png");
  expectErrorNaming(config_, "no 9x6 board found in any of the 2 images");
}

TEST_F(CalibrateTool, NoMatchingImageIsAnError) {
  config_.points.clear();
  config_.images = path("none*.jpg");
  expectErrorNaming(config_, "no image matches");
}

}  // namespace
}  // namespace lineloc
