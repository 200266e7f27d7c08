// The front end allocates nothing from the C++ heap once its buffers have
// grown to the frame size: operator new is counted during a second frame.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "robot/vision/features/feature_extractor.h"
#include "synthetic_scene.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

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

TEST(FeatureExtractorSteadyState, SecondFrameAllocatesNothing) {
  const testing::SceneOptions options;
  const testing::SyntheticScene first = testing::renderRectangles(options, 5, 31);
  const testing::SyntheticScene second = testing::renderRectangles(options, 5, 31);
  CameraCalibration calibration;
  calibration.camera = {300.0, 300.0, 159.5, 119.5, 0.0, options.size.width, options.size.height};
  FeatureExtractor extractor(calibration);
  extractor.extract(first.image);
  const long before = g_allocations.load();
  const size_t segments = extractor.extract(second.image).segments.size();
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_GT(segments, 0u);
}

}  // namespace
}  // namespace lineloc
