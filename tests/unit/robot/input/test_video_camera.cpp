// VideoCamera: a video file plays as a camera delivers, every frame as it was
// written (a lossless codec), each stamped on the robot's time base at its
// presentation time since the first; a source that is no camera and a
// control the device does not have are refused, named.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "common/time/clock.h"
#include "robot/input/video_camera.h"

namespace lineloc {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 15;
constexpr double kFps = 20.0;

// Frame i: a grey ramp offset by 7 i, so that every frame differs everywhere.
cv::Mat frameImage(int i) {
  cv::Mat image(48, 64, CV_8UC3);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const auto grey = static_cast<uchar>((x + 2 * y + 7 * i) % 256);
      image.at<cv::Vec3b>(y, x) = cv::Vec3b(grey, grey, grey);
    }
  }
  return image;
}

class VideoCameraTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = fs::temp_directory_path() / ("video_camera_" + std::to_string(getpid()));
    fs::create_directories(folder_);
    video_ = (folder_ / "drive.mkv").string();
    cv::VideoWriter writer(video_, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('F', 'F', 'V', '1'),
                           kFps, cv::Size(64, 48));
    ASSERT_TRUE(writer.isOpened());
    for (int i = 0; i < kFrames; ++i) {
      writer.write(frameImage(i));
    }
  }
  static void TearDownTestSuite() { fs::remove_all(folder_); }

  static fs::path folder_;
  static std::string video_;
};

fs::path VideoCameraTest::folder_;
std::string VideoCameraTest::video_;

TEST_F(VideoCameraTest, AFilePlaysInRealTimeEveryFrameAsWritten) {
  const RobotTimeBase time_base;
  VideoCamera camera({video_}, time_base);
  std::vector<CapturedFrame> frames;
  const int64_t start_ns = time_base.now();
  while (std::optional<CapturedFrame> frame = camera.read()) {
    frames.push_back(std::move(*frame));
  }
  ASSERT_EQ(frames.size(), static_cast<size_t>(kFrames));
  const int64_t period_ns = static_cast<int64_t>(1e9 / kFps);
  for (int i = 0; i < kFrames; ++i) {
    cv::Mat grey;
    cv::cvtColor(frames[i].image, grey, cv::COLOR_BGR2GRAY);
    cv::Mat expected;
    cv::cvtColor(frameImage(i), expected, cv::COLOR_BGR2GRAY);
    EXPECT_EQ(cv::norm(grey, expected, cv::NORM_INF), 0.0) << i;
    // Stamped at its presentation time from the first frame's (to the drift
    // a DeviceClock allows, 200 ppm), and not handed over before it.
    EXPECT_NEAR(static_cast<double>(frames[i].stamp_ns - frames[0].stamp_ns),
                static_cast<double>(i * period_ns),
                2e-4 * static_cast<double>(frames[i].arrival_ns - frames[0].arrival_ns) + 1e3)
        << i;
    EXPECT_GE(frames[i].arrival_ns, frames[0].arrival_ns + i * period_ns) << i;
    EXPECT_GE(frames[i].arrival_ns, frames[i].stamp_ns) << i;
  }
  // Played in real time: the whole file took its length.
  EXPECT_GE(frames.back().arrival_ns - start_ns, (kFrames - 1) * period_ns);
}

TEST_F(VideoCameraTest, NoCameraAndAControlTheDeviceLacksAreRefusedNamed) {
  const RobotTimeBase time_base;
  try {
    VideoCamera camera({(folder_ / "missing.mkv").string()}, time_base);
    FAIL() << "a missing file opened";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("camera_source"), std::string::npos) << error.what();
  }
  VideoCameraOptions options{video_};
  options.gain = 4.0;
  try {
    VideoCamera camera(options, time_base);
    FAIL() << "a video file took a gain";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("camera_gain"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace lineloc
