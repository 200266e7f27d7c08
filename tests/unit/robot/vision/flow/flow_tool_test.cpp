// lineloc-flow's pipeline on images of known motion: a textured frame with a
// square of it moved, as flow, and a frame shifted, as a rectified stereo
// pair; the files it writes must hold that motion, and bad input be named.
#include "robot/vision/flow/flow_tool.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <vector>

#include "robot/vision/flow/flo_io.h"
#include "robot/vision/stereo/pfm_io.h"

namespace lineloc {
namespace {

namespace fs = std::filesystem;

// Blurred random texture, 320 x 240, and the same frame with the square
// (112, 64)-(208, 160) of its texture moved by (dx, dy) px; `whole` moves the
// whole frame (a stereo pair).
std::pair<cv::Mat, cv::Mat> shiftedPair(int dx, int dy, bool whole) {
  cv::Mat texture(240 + 2 * 16, 320 + 2 * 16, CV_8UC1);
  cv::RNG rng(5);
  rng.fill(texture, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(texture, texture, cv::Size(), 1.5);
  const cv::Mat first = texture(cv::Rect(16, 16, 320, 240)).clone();
  const cv::Mat moved = texture(cv::Rect(16 - dx, 16 - dy, 320, 240)).clone();
  if (whole) {
    return {first, moved};
  }
  cv::Mat second = first.clone();
  const cv::Rect square(112, 64, 96, 96);
  moved(square).copyTo(second(square));
  return {first, second};
}

class FlowTool : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("flow_tool_" + std::to_string(getpid()));
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  std::vector<std::string> writePair(int dx, int dy, bool whole) {
    const auto [a, b] = shiftedPair(dx, dy, whole);
    const std::string first = (folder_ / "a.png").string();
    const std::string second = (folder_ / "b.png").string();
    cv::imwrite(first, a);
    cv::imwrite(second, b);
    return {first, second};
  }

  fs::path folder_;
};

TEST_F(FlowTool, FlowOfAShiftedFrameIsTheShift) {
  FlowToolConfig config;
  config.images = writePair(3, -2, false);
  config.out = (folder_ / "flow.png").string();
  config.flo = (folder_ / "flow.flo").string();
  std::ostringstream out;
  runFlowTool(config, out);
  const cv::Mat flow = readFlo(config.flo);
  ASSERT_EQ(flow.size(), cv::Size(320, 240));
  // A block inside the moving square, and one outside it.
  const cv::Vec2f moving = flow.at<cv::Vec2f>(120, 160);
  EXPECT_NEAR(moving[0], 3.0f, 0.1f);
  EXPECT_NEAR(moving[1], -2.0f, 0.1f);
  const cv::Vec2f still = flow.at<cv::Vec2f>(20, 20);
  EXPECT_EQ(still, cv::Vec2f(0.0f, 0.0f));
  EXPECT_FALSE(cv::imread(config.out).empty());
  EXPECT_NE(out.str().find("blocks moving"), std::string::npos) << out.str();
}

TEST_F(FlowTool, DisparityOfAShiftedPairIsTheShift) {
  FlowToolConfig config;
  config.stereo = true;
  // The right camera sees a point 7 px further left.
  config.images = writePair(-7, 0, true);
  config.out = (folder_ / "disparity.png").string();
  config.pfm = (folder_ / "disparity.pfm").string();
  std::ostringstream out;
  runFlowTool(config, out);
  const cv::Mat disparity = readPfm(config.pfm);
  ASSERT_EQ(disparity.size(), cv::Size(320, 240));
  EXPECT_NEAR(disparity.at<float>(120, 160), 7.0f, 0.5f);
}

TEST_F(FlowTool, NamesWhatIsWrong) {
  FlowToolConfig config;
  config.images = {(folder_ / "missing.png").string(), (folder_ / "missing.png").string()};
  std::ostringstream out;
  try {
    runFlowTool(config, out);
    FAIL() << "a missing image accepted";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("missing.png"), std::string::npos) << error.what();
  }
  // A JPEG header claiming 20000 x 20000 pixels is refused before decoding.
  std::vector<uint8_t> jpeg;
  cv::imencode(".jpg", cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(128)), jpeg);
  std::string huge(jpeg.begin(), jpeg.end());
  huge.replace(huge.find("\xFF\xC0") + 5, 4, "\x4E\x20\x4E\x20");
  std::ofstream(folder_ / "huge.jpg", std::ios::binary) << huge;
  config.images = {(folder_ / "huge.jpg").string(), (folder_ / "huge.jpg").string()};
  try {
    runFlowTool(config, out);
    FAIL() << "a 400-megapixel image accepted";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("huge.jpg': its JPEG header claims 20000 x 20000"),
              std::string::npos)
        << error.what();
  }
  config.images = writePair(1, 1, false);
  config.simd_path = "neon";
  EXPECT_THROW(runFlowTool(config, out), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
