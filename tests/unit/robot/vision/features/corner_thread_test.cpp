// The front end with its corners on a thread of their own gives exactly the
// features of one thread, which streams the corners with the gradient rows:
// the same segments and the same corners, bit for bit, frame after frame, on
// real photographs seen through a lens with barrel distortion.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "robot/vision/features/feature_extractor.h"
#include "tests/unit/robot/vision/sample_images.h"

namespace lineloc {
namespace {

const cv::Size kFrameSize(640, 480);

CameraCalibration barrelCamera() {
  CameraCalibration calibration;
  calibration.camera = {500.0, 500.0, 319.5, 239.5, 0.0, kFrameSize.width, kFrameSize.height};
  calibration.distortion = {-0.25, 0.07, 0.0, 0.0};
  return calibration;
}

std::vector<cv::Mat> frames() {
  std::vector<cv::Mat> frames;
  for (const std::string name : {"building.jpg", "left01.jpg", "box_in_scene.png"}) {
    cv::Mat frame;
    cv::resize(readSampleImage(name, cv::IMREAD_GRAYSCALE), frame, kFrameSize, 0.0, 0.0,
               cv::INTER_AREA);
    frames.push_back(frame);
  }
  return frames;
}

void expectSame(const ImageSegment& a, const ImageSegment& b) {
  EXPECT_EQ(a.start, b.start);
  EXPECT_EQ(a.end, b.end);
  EXPECT_EQ(a.start_covariance, b.start_covariance);
  EXPECT_EQ(a.end_covariance, b.end_covariance);
  EXPECT_EQ(a.contrast, b.contrast);
  EXPECT_EQ(a.polarity, b.polarity);
}

void expectSame(const ImageCorner& a, const ImageCorner& b) {
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.covariance, b.covariance);
  EXPECT_EQ(a.strength, b.strength);
}

TEST(CornerThread, GivesTheFeaturesOfOneThread) {
  FeatureExtractorOptions one_thread;
  one_thread.corners_on_own_thread = false;
  FeatureExtractor streamed(barrelCamera(), one_thread);
  FeatureExtractor beside(barrelCamera());
  const std::vector<cv::Mat> sequence = frames();
  size_t corners = 0;
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t i = 0; i < sequence.size(); ++i) {
      SCOPED_TRACE("frame " + std::to_string(i) + " of pass " + std::to_string(pass));
      const FrameFeatures& expected = streamed.extract(sequence[i]);
      const FrameFeatures& actual = beside.extract(sequence[i]);
      ASSERT_EQ(actual.segments.size(), expected.segments.size());
      ASSERT_EQ(actual.corners.size(), expected.corners.size());
      for (size_t k = 0; k < expected.segments.size(); ++k) {
        expectSame(actual.segments[k], expected.segments[k]);
      }
      for (size_t k = 0; k < expected.corners.size(); ++k) {
        expectSame(actual.corners[k], expected.corners[k]);
      }
      corners += expected.corners.size();
    }
  }
  EXPECT_GT(corners, 100u);
}

}  // namespace
}  // namespace lineloc
