// The front end allocates nothing from the C++ heap once its buffers have
// grown to the frames it sees: operator new is counted while a sequence of
// different frames, each seen once before, is processed again three times.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include "robot/vision/features/feature_extractor.h"
#include "synthetic_scene.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// operator new below is malloc and operator delete is free, a matched pair
// GCC cannot see through once they are inlined into each other's callers.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) {
    return p;
  }
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace lineloc {
namespace {

TEST(FeatureExtractorSteadyState, RepeatedFramesAllocateNothing) {
  const testing::SceneOptions options;
  std::vector<cv::Mat> frames;
  for (uint32_t seed = 31; seed <= 34; ++seed) {
    frames.push_back(testing::renderRectangles(options, 5, seed).image);
  }
  CameraCalibration calibration;
  calibration.camera = {300.0, 300.0, 159.5, 119.5, 0.0, options.size.width, options.size.height};
  calibration.distortion = {-0.2, 0.05, 0.0, 0.0};
  FeatureExtractor extractor(calibration);
  for (const cv::Mat& frame : frames) {
    extractor.extract(frame);
  }
  const long before = g_allocations.load();
  size_t segments = 0;
  for (int pass = 0; pass < 3; ++pass) {
    for (const cv::Mat& frame : frames) {
      segments += extractor.extract(frame).segments.size();
    }
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_GT(segments, 0u);
}

}  // namespace
}  // namespace lineloc
