// The front end's SIMD kernels are compiled for every instruction set Highway
// targets here, down to plain scalar code (the path a processor with SSE2 only
// takes), and dispatched at run time. Each target must give the same features:
// the same segments and corners, positions equal to 1e-3 px (targets that fuse
// multiply-adds round the sub-pixel offsets differently in the last bits).
#include <gtest/gtest.h>
#include <hwy/highway.h>
#include <hwy/targets.h>

#include "robot/vision/features/feature_extractor.h"
#include "synthetic_scene.h"

namespace lineloc {
namespace {

constexpr float kTolerancePx = 1e-3f;

bool near(const Eigen::Vector2f& a, const Eigen::Vector2f& b) {
  return (a - b).norm() <= kTolerancePx;
}

bool hasSegment(const std::vector<ImageSegment>& segments, const ImageSegment& wanted) {
  return std::any_of(segments.begin(), segments.end(), [&](const ImageSegment& s) {
    return (near(s.start, wanted.start) && near(s.end, wanted.end)) ||
           (near(s.start, wanted.end) && near(s.end, wanted.start));
  });
}

bool hasCorner(const std::vector<ImageCorner>& corners, const ImageCorner& wanted) {
  return std::any_of(corners.begin(), corners.end(),
                     [&](const ImageCorner& c) { return near(c.position, wanted.position); });
}

class SupportedTargetsReset {
 public:
  ~SupportedTargetsReset() { hwy::SetSupportedTargetsForTest(0); }
};

TEST(FeatureExtractorSimd, EveryInstructionSetGivesTheSameFeatures) {
  testing::SceneOptions options;
  const testing::SyntheticScene scene = testing::renderRectangles(options, 5, 41);
  CameraCalibration calibration;
  calibration.camera = {300.0, 300.0, 159.5, 119.5, 0.0, options.size.width, options.size.height};
  calibration.distortion = {-0.1, 0.02, 0.0, 0.0};
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_GE(targets.size(), 2u) << "expected the scalar path and at least one SIMD target";
  const SupportedTargetsReset reset;
  std::vector<FrameFeatures> results;
  for (const int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    FeatureExtractor extractor(calibration);
    results.push_back(extractor.extract(scene.image));
  }
  const FrameFeatures& reference = results.back();  // the lowest target: scalar code
  ASSERT_GE(reference.segments.size(), 16u);
  ASSERT_GE(reference.corners.size(), 16u);
  for (size_t t = 0; t + 1 < results.size(); ++t) {
    const FrameFeatures& features = results[t];
    const char* name = hwy::TargetName(targets[t]);
    ASSERT_EQ(features.segments.size(), reference.segments.size()) << name;
    ASSERT_EQ(features.corners.size(), reference.corners.size()) << name;
    for (const ImageSegment& segment : features.segments) {
      EXPECT_TRUE(hasSegment(reference.segments, segment)) << name;
    }
    for (const ImageCorner& corner : features.corners) {
      EXPECT_TRUE(hasCorner(reference.corners, corner)) << name;
    }
  }
}

}  // namespace
}  // namespace lineloc
