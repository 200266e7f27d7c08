// The robot's front end options (frontEndOptions): its thresholds lowered to
// 4 and 5, it keeps a step between two walls in shade that its defaults drop
// (16 grey levels: a gradient of 5.4 per pixel once smoothed), and still
// finds no segment in a camera's noise alone.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "robot/agent/robot_agent.h"

namespace lineloc {
namespace {

const cv::Size kFrameSize(640, 480);
// lineloc-sim's pixel noise (grey levels).
constexpr double kSimulatedNoiseSigma = 2.0;

CameraCalibration idealCamera() {
  CameraCalibration calibration;
  calibration.camera = {500.0, 500.0, 319.5, 239.5, 0.0, kFrameSize.width, kFrameSize.height};
  return calibration;
}

// Two shaded walls meeting at column 320, `step` grey levels apart, under
// Gaussian pixel noise of `noise_sigma`.
cv::Mat shadedCorner(double step, double noise_sigma) {
  cv::Mat image(kFrameSize, CV_32F, cv::Scalar(60.0));
  image(cv::Rect(320, 0, 320, kFrameSize.height)).setTo(60.0 + step);
  cv::Mat noise(kFrameSize, CV_32F);
  cv::setRNGSeed(7);
  cv::randn(noise, 0.0, noise_sigma);
  cv::Mat grey;
  cv::Mat(image + noise).convertTo(grey, CV_8U);
  return grey;
}

// Segments along column 320 at least `min_length_px` long.
int stepSegments(const FrameFeatures& features, float min_length_px) {
  int count = 0;
  for (const ImageSegment& segment : features.segments) {
    const bool on_step =
        std::abs(segment.start.x() - 320.0f) < 1.5f && std::abs(segment.end.x() - 320.0f) < 1.5f;
    count += on_step && (segment.end - segment.start).norm() >= min_length_px ? 1 : 0;
  }
  return count;
}

// The robot's configuration with the weak-edge thresholds.
RobotConfig weakEdges() {
  RobotConfig config;
  config.min_edge_gradient = 4.0;
  config.min_segment_contrast = 5.0;
  return config;
}

TEST(FrontEndOptions, LoweredThresholdsKeepTheStepBetweenTwoWallsInShade) {
  const cv::Mat image = shadedCorner(16.0, kSimulatedNoiseSigma);
  FeatureExtractor weak(idealCamera(), frontEndOptions(weakEdges()));
  EXPECT_EQ(stepSegments(weak.extract(image), 200.0f), 1);
  FeatureExtractor defaults(idealCamera(), frontEndOptions(RobotConfig{}));
  EXPECT_EQ(stepSegments(defaults.extract(image), 20.0f), 0);
}

TEST(FrontEndOptions, LoweredThresholdsFindNoSegmentInNoiseTwiceTheSimulatedCamerasAlone) {
  FeatureExtractor weak(idealCamera(), frontEndOptions(weakEdges()));
  EXPECT_TRUE(weak.extract(shadedCorner(0.0, 2.0 * kSimulatedNoiseSigma)).segments.empty());
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
