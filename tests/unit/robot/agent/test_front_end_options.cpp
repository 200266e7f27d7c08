// The robot's front end options (frontEndOptions): with its default
// thresholds (4 and 5) it keeps a step between two walls in shade that an
// edge threshold of 8 drops (16 grey levels: a gradient of 5.4 per pixel once
// smoothed), and still finds no segment in a camera's noise alone.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "robot/agent/robot_agent.h"

namespace lineloc {
namespace {

const cv::Size kFrameSize(640, 480);
// Where the two walls meet.
constexpr int kStepColumn = 320;
// lineloc-sim's pixel noise (grey levels).
constexpr double kSimulatedNoiseSigma = 2.0;

CameraCalibration idealCamera() {
  CameraCalibration calibration;
  calibration.camera = {500.0, 500.0, 319.5, 239.5, 0.0, kFrameSize.width, kFrameSize.height};
  return calibration;
}

// Two shaded walls meeting at kStepColumn, `step` grey levels apart, under
// Gaussian pixel noise of `noise_sigma`.
cv::Mat shadedCorner(double step, double noise_sigma) {
  cv::Mat image(kFrameSize, CV_32F, cv::Scalar(60.0));
  image(cv::Rect(kStepColumn, 0, kFrameSize.width - kStepColumn, kFrameSize.height))
      .setTo(60.0 + step);
  cv::Mat noise(kFrameSize, CV_32F);
  cv::setRNGSeed(7);
  cv::randn(noise, 0.0, noise_sigma);
  cv::Mat grey;
  cv::Mat(image + noise).convertTo(grey, CV_8U);
  return grey;
}

// Segments along kStepColumn at least `min_length_px` long.
int stepSegments(const FrameFeatures& features, float min_length_px) {
  int count = 0;
  for (const ImageSegment& segment : features.segments) {
    const bool on_step = std::abs(segment.start.x() - kStepColumn) < 1.5f &&
                         std::abs(segment.end.x() - kStepColumn) < 1.5f;
    count += on_step && (segment.end - segment.start).norm() >= min_length_px ? 1 : 0;
  }
  return count;
}

// The robot's configuration with the thresholds of the vision library's
// defaults (EdgeDetectorOptions, LineExtractorOptions).
RobotConfig strongEdgesOnly() {
  RobotConfig config;
  config.min_edge_gradient = 8.0;
  config.min_segment_contrast = 10.0;
  return config;
}

TEST(FrontEndOptions, TheDefaultsKeepTheStepBetweenTwoWallsInShade) {
  const cv::Mat image = shadedCorner(16.0, kSimulatedNoiseSigma);
  const RobotConfig config;
  FeatureExtractor defaults(idealCamera(), frontEndOptions(config));
  EXPECT_EQ(stepSegments(defaults.extract(image), 200.0f), 1);
  FeatureExtractor strong(idealCamera(), frontEndOptions(strongEdgesOnly()));
  EXPECT_EQ(stepSegments(strong.extract(image), 20.0f), 0);
}

TEST(FrontEndOptions, TheDefaultsFindNoSegmentInNoiseTwiceTheSimulatedCamerasAlone) {
  const RobotConfig config;
  FeatureExtractor defaults(idealCamera(), frontEndOptions(config));
  EXPECT_TRUE(defaults.extract(shadedCorner(0.0, 2.0 * kSimulatedNoiseSigma)).segments.empty());
}

TEST(FrontEndOptions, TakeTheConfiguredThresholds) {
  RobotConfig config;
  config.min_edge_gradient = 12.0;
  config.min_segment_contrast = 15.0;
  config.min_segment_length_px = 30.0;
  const FeatureExtractorOptions options = frontEndOptions(config);
  EXPECT_EQ(options.edges.min_gradient, 12.0f);
  EXPECT_EQ(options.lines.min_contrast, 15.0);
  EXPECT_EQ(options.lines.min_length_px, 30.0);
}

TEST(FrontEndOptions, AnOutOfRangeThresholdIsRejected) {
  RobotConfig config;
  config.min_edge_gradient = 0.0;
  EXPECT_THROW(FeatureExtractor(idealCamera(), frontEndOptions(config)), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
