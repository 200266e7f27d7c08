// lineloc-features' pipeline on a synthetic image of known noise and edges:
// it reports the noise it estimated, sends the scene's edges and writes the
// overlay; an unreadable image is named.
#include "robot/vision/features/features_tool.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "tests/unit/robot/vision/support/synthetic_scene.h"

namespace lineloc {
namespace {

namespace fs = std::filesystem;

int countLines(const std::string& text, const std::string& record) {
  std::istringstream in(text);
  int count = 0;
  for (std::string line; std::getline(in, line);) {
    count += line.rfind(record + " ", 0) == 0 ? 1 : 0;
  }
  return count;
}

TEST(FeaturesTool, SendsTheEdgesOfASceneOfKnownNoise) {
  const fs::path folder = fs::temp_directory_path() / ("features_tool_" + std::to_string(getpid()));
  fs::create_directories(folder);
  testing::SceneOptions scene_options;
  scene_options.size = {640, 480};
  scene_options.noise_sigma = 3.0;
  const testing::SyntheticScene scene = testing::renderRectangles(scene_options, 6, 7);
  FeaturesToolConfig config;
  config.image = (folder / "scene.png").string();
  config.out = (folder / "overlay.png").string();
  ASSERT_TRUE(cv::imwrite(config.image, scene.image));
  std::ostringstream out;
  const FeaturesToolSummary summary = runFeaturesTool(config, out);
  // The estimate holds the noise within 10 %; the blur lowers it little.
  EXPECT_NEAR(summary.noise_sigma, scene_options.noise_sigma, 0.1 * scene_options.noise_sigma);
  // Six rectangles have 24 sides; each is sent, in one or more pieces.
  EXPECT_GE(summary.segments, 24u);
  EXPECT_EQ(countLines(out.str(), "segment"), static_cast<int>(summary.segments));
  EXPECT_EQ(countLines(out.str(), "corner"), static_cast<int>(summary.corners));
  const cv::Mat overlay = cv::imread(config.out, cv::IMREAD_COLOR);
  EXPECT_EQ(overlay.size(), scene.image.size());
  fs::remove_all(folder);
}

TEST(FeaturesTool, NamesAnImageItCannotRead) {
  FeaturesToolConfig config;
  config.image = "no_such_image.png";
  std::ostringstream out;
  try {
    runFeaturesTool(config, out);
    FAIL() << "a missing image accepted";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("no_such_image.png"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace lineloc
