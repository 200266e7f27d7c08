#include "robot/vision/lines/segment_validation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace lineloc {
namespace {

const cv::Size kImageSize(640, 480);
constexpr double kPoints = 40.0;

LineSegment segmentOfContrast(double contrast) {
  LineSegment segment;
  segment.moments.n = kPoints;
  segment.step_sum = contrast * kPoints;
  return segment;
}

struct NullModel {
  double mean, sigma;  // of a segment's contrast under noise alone
};

NullModel nullModel(const EdgeNoise& noise) {
  const double spread = std::sqrt(std::min(1.0, noise.correlation_length_px / kPoints));
  return {std::sqrt(2.0 / M_PI) * noise.step_sigma,
          std::sqrt(1.0 - 2.0 / M_PI) * noise.step_sigma * spread};
}

EdgeNoise edgeNoise(double image_sigma) {
  return EdgeDetector(EdgeDetectorOptions{}).noise(image_sigma);
}

// (640 x 480)^2 tests: NFA = 9.4e10 P(Z >= z) is 1 at z = 6.7; at z = 6 it is
// 93 and at z = 7.5 it is 3e-3.
TEST(SegmentValidation, FlipsWhereTheNoiseExplainsTheContrast) {
  for (const double sigma : {0.5, 2.0, 8.0}) {
    const EdgeNoise noise = edgeNoise(sigma);
    const NullModel null = nullModel(noise);
    const SegmentValidation validation(kImageSize, noise, 1.0);
    EXPECT_TRUE(validation.meaningful(segmentOfContrast(null.mean + 7.5 * null.sigma))) << sigma;
    EXPECT_FALSE(validation.meaningful(segmentOfContrast(null.mean + 6.0 * null.sigma))) << sigma;
    EXPECT_NEAR(validation.log10FalseAlarms(segmentOfContrast(null.mean + 6.0 * null.sigma)),
                std::log10(93.0), 0.05);
  }
}

TEST(SegmentValidation, ContrastKeptInCleanImageIsRejectedInNoisyOne) {
  const double contrast = 4.0;
  EXPECT_TRUE(
      SegmentValidation(kImageSize, edgeNoise(1.0), 1.0).meaningful(segmentOfContrast(contrast)));
  EXPECT_FALSE(
      SegmentValidation(kImageSize, edgeNoise(10.0), 1.0).meaningful(segmentOfContrast(contrast)));
}

TEST(SegmentValidation, LongerSegmentsNeedLessContrast) {
  const SegmentValidation validation(kImageSize, edgeNoise(4.0), 1.0);
  LineSegment longer = segmentOfContrast(2.0);
  longer.moments.n = 400.0;
  longer.step_sum = 2.0 * longer.moments.n;
  EXPECT_FALSE(validation.meaningful(segmentOfContrast(2.0)));
  EXPECT_TRUE(validation.meaningful(longer));
}

TEST(SegmentValidation, NoiseModelOfTheSmoothedStep) {
  // sigma 1 px smoothing: sum w^2 ~ 1 / (2 sqrt(pi)), the continuous Gaussian's.
  const EdgeNoise noise = edgeNoise(1.0);
  const double sum_w2 = 1.0 / (2.0 * std::sqrt(M_PI));
  EXPECT_NEAR(noise.correlation_length_px, 1.0 / sum_w2, 0.1 / sum_w2);
  EXPECT_NEAR(noise.step_sigma, std::sqrt(2.0) * sum_w2, 0.1 * std::sqrt(2.0) * sum_w2);
}

TEST(SegmentValidation, RejectsNonPositiveEpsilon) {
  EXPECT_THROW(SegmentValidation(kImageSize, edgeNoise(1.0), 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
