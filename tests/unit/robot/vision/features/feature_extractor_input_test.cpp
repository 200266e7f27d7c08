#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "robot/vision/features/feature_extractor.h"
#include "synthetic_scene.h"

namespace lineloc {
namespace {

CameraCalibration idealCamera(int width, int height) {
  CameraCalibration calibration;
  calibration.camera = {300.0, 300.0, 0.5 * (width - 1), 0.5 * (height - 1), 0.0, width, height};
  return calibration;
}

void expectInvalid(FeatureExtractor& extractor, const cv::Mat& image, const std::string& words) {
  try {
    extractor.extract(image);
    FAIL() << "accepted an image that should be refused (" << words << ")";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
  }
}

TEST(FeatureExtractorInput, RefusesBadImagesWithAClearError) {
  FeatureExtractor extractor(idealCamera(64, 48));
  expectInvalid(extractor, cv::Mat(), "empty");
  expectInvalid(extractor, cv::Mat(48, 64, CV_16UC1, cv::Scalar(0)), "8-bit");
  expectInvalid(extractor, cv::Mat(48, 64, CV_32FC1, cv::Scalar(0)), "8-bit");
  expectInvalid(extractor, cv::Mat(48, 64, CV_8UC2, cv::Scalar(0)), "channels");
  expectInvalid(extractor, cv::Mat(47, 64, CV_8UC1, cv::Scalar(0)), "64x48");
  expectInvalid(extractor, cv::Mat(480, 640, CV_8UC1, cv::Scalar(0)), "64x48");
}

TEST(FeatureExtractorInput, RefusesTinyAndHugeCalibrations) {
  EXPECT_THROW(FeatureExtractor(idealCamera(8, 8)), std::invalid_argument);
  EXPECT_THROW(FeatureExtractor(idealCamera(FeatureExtractor::kMaxImageSidePx + 1, 100)),
               std::invalid_argument);
  EXPECT_THROW(FeatureExtractor(idealCamera(0, 0)), std::invalid_argument);
}

TEST(FeatureExtractorInput, BlankAndSaturatedFramesGiveEmptySets) {
  FeatureExtractor extractor(idealCamera(160, 120));
  for (const double grey : {0.0, 128.0, 255.0}) {
    const FrameFeatures& features = extractor.extract(cv::Mat(120, 160, CV_8UC1, cv::Scalar(grey)));
    EXPECT_TRUE(features.segments.empty()) << grey;
    EXPECT_TRUE(features.corners.empty()) << grey;
  }
}

TEST(FeatureExtractorInput, ColourInputGivesTheSameFeaturesAsItsGreyConversion) {
  testing::SceneOptions options;
  const testing::SyntheticScene scene = testing::renderRectangles(options, 4, 11);
  FeatureExtractor extractor(idealCamera(options.size.width, options.size.height));
  const FrameFeatures grey = extractor.extract(scene.image);
  cv::Mat colour;
  cv::cvtColor(scene.image, colour, cv::COLOR_GRAY2BGR);
  const FrameFeatures from_colour = extractor.extract(colour);
  ASSERT_FALSE(grey.segments.empty());
  ASSERT_EQ(grey.segments.size(), from_colour.segments.size());
  for (size_t i = 0; i < grey.segments.size(); ++i) {
    EXPECT_EQ(grey.segments[i].start, from_colour.segments[i].start);
    EXPECT_EQ(grey.segments[i].end, from_colour.segments[i].end);
  }
  EXPECT_EQ(grey.corners.size(), from_colour.corners.size());
}

// Buffers are reused: a second frame of the same size keeps every output
// array where it was (no reallocation), and the result is the same.
TEST(FeatureExtractorInput, ReusesItsBuffersFrameToFrame) {
  testing::SceneOptions options;
  const testing::SyntheticScene scene = testing::renderRectangles(options, 4, 12);
  FeatureExtractor extractor(idealCamera(options.size.width, options.size.height));
  const FrameFeatures& first = extractor.extract(scene.image);
  const ImageSegment* segments = first.segments.data();
  const ImageCorner* corners = first.corners.data();
  const size_t segment_count = first.segments.size();
  const FrameFeatures& second = extractor.extract(scene.image);
  EXPECT_EQ(&first, &second);
  EXPECT_EQ(segments, second.segments.data());
  EXPECT_EQ(corners, second.corners.data());
  EXPECT_EQ(segment_count, second.segments.size());
}

TEST(FeatureExtractorInput, SegmentsCarryPolarityAndContrast) {
  // A bright square on a dark background: every edge has the bright side inside.
  testing::SceneOptions options;
  options.noise_sigma = 1.0;
  const testing::SyntheticScene scene = testing::renderPolygons(
      options, 40.0, {{{{100.0, 60.0}, {220.0, 60.0}, {220.0, 180.0}, {100.0, 180.0}}, 200.0}}, 3);
  FeatureExtractor extractor(idealCamera(options.size.width, options.size.height));
  const FrameFeatures& features = extractor.extract(scene.image);
  ASSERT_EQ(features.segments.size(), 4u);
  const Eigen::Vector2f centre(160.0f, 120.0f);
  for (const ImageSegment& segment : features.segments) {
    const Eigen::Vector2f d = segment.end - segment.start;
    const Eigen::Vector2f left(d.y(), -d.x());
    const int centre_side = left.dot(centre - segment.start) > 0.0f ? 1 : -1;
    EXPECT_EQ(segment.polarity, centre_side);
    // Step of 160 grey levels sampled 3 px either side of an edge blurred to
    // s = sqrt(1^2 + 1^2) px (lens + pre-smoothing): 160 erf(3 / (sqrt(2) s))
    // = 160 erf(1.5) = 154.6. The mean of >= 100 samples of noise sigma 1
    // (difference sigma 1.4) is good to 0.2; 2 grey levels also cover the
    // 8-bit rounding of the smoothed image.
    EXPECT_NEAR(segment.contrast, 160.0f * std::erf(1.5f), 2.0f);
  }
}

}  // namespace
}  // namespace lineloc
