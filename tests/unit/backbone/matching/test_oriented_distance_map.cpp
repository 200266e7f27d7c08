// The oriented distance map: distances to segments of a similar direction,
// truncated, and nothing but the truncation for anything outside the image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "backbone/matching/oriented_distance_map.h"

namespace lineloc {
namespace {

constexpr double kHorizontal = 0.0;
constexpr double kVertical = M_PI / 2.0;
// The maps below truncate at 10 px and keep distances in 255 levels.
// Half a level of the 10 px truncation, plus the single-precision rounding of
// the distance (oriented_distance_map.h).
constexpr double kHalfLevelPx = 10.0 / 255.0 / 2.0 + 1e-4;

ImageSegment segment(float x0, float y0, float x1, float y1) {
  ImageSegment s;
  s.start = {x0, y0};
  s.end = {x1, y1};
  return s;
}

OrientedDistanceMap horizontalAt100(int downsample) {
  return OrientedDistanceMap({segment(100, 100, 300, 100)}, 640, 480, {15.0, 10.0, downsample});
}

TEST(OrientedDistanceMap, MeasuresTheDistanceToASegmentOfTheSameDirection) {
  const OrientedDistanceMap map = horizontalAt100(1);
  EXPECT_NEAR(map.distance({200, 100}, kHorizontal), 0.0, kHalfLevelPx);
  // Exact Euclidean distances, also past a segment's end.
  EXPECT_NEAR(map.distance({200, 106}, kHorizontal), 6.0, kHalfLevelPx);
  EXPECT_NEAR(map.distance({200, 94}, M_PI), 6.0, kHalfLevelPx);  // direction is taken mod pi
  EXPECT_NEAR(map.distance({304, 103}, kHorizontal), 5.0, kHalfLevelPx);
  EXPECT_NEAR(map.distance({96, 97}, kHorizontal), 5.0, kHalfLevelPx);
  EXPECT_FLOAT_EQ(map.distance({200, 150}, kHorizontal), 10.0f);  // truncated
}

double distanceToSegment(const Eigen::Vector2d& q, const ImageSegment& s) {
  const Eigen::Vector2d a = s.start.cast<double>();
  const Eigen::Vector2d along = s.end.cast<double>() - a;
  const double t = std::clamp((q - a).dot(along) / along.squaredNorm(), 0.0, 1.0);
  return (q - a - t * along).norm();
}

// Every cell against the exact truncated distance to the nearest of a few
// random segments of one direction, some reaching beyond the image, at full
// and half resolution: within half a level.
TEST(OrientedDistanceMap, EveryCellHoldsTheExactTruncatedDistance) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> position(-40.0, 360.0);
  std::uniform_real_distribution<double> length(15.0, 200.0);
  for (const double direction_deg : {0.0, 30.0, 90.0, 137.0, 179.0}) {
    const double direction = direction_deg * M_PI / 180.0;
    std::vector<ImageSegment> segments;
    for (int k = 0; k < 6; ++k) {
      const double x = position(random);
      const double y = position(random) * 0.75;
      const double l = length(random);
      segments.push_back(segment(static_cast<float>(x), static_cast<float>(y),
                                 static_cast<float>(x + l * std::cos(direction)),
                                 static_cast<float>(y + l * std::sin(direction))));
    }
    for (const int downsample : {1, 2}) {
      const OrientedDistanceMap map(segments, 320, 240, {15.0, 10.0, downsample});
      for (int row = 0; row < 240 / downsample; ++row) {
        for (int col = 0; col < 320 / downsample; ++col) {
          const Eigen::Vector2d q(col * downsample, row * downsample);
          double exact = 10.0;
          for (const ImageSegment& s : segments) {
            exact = std::min(exact, distanceToSegment(q, s));
          }
          ASSERT_NEAR(map.distance(q, direction), exact, kHalfLevelPx)
              << direction_deg << " deg, downsample " << downsample << ", cell " << col << ", "
              << row;
        }
      }
    }
  }
}

TEST(OrientedDistanceMap, IgnoresSegmentsOfAnotherDirection) {
  const OrientedDistanceMap map = horizontalAt100(1);
  EXPECT_FLOAT_EQ(map.distance({200, 100}, kVertical), 10.0f);
  // Within half a bin (11.25 degrees) the segment is always seen.
  EXPECT_NEAR(map.distance({200, 100}, 11.0 * M_PI / 180.0), 0.0, 1e-6);
  EXPECT_NEAR(map.distance({200, 100}, -11.0 * M_PI / 180.0), 0.0, 1e-6);
  // Beyond one and a half bins (33.75 degrees) never.
  EXPECT_FLOAT_EQ(map.distance({200, 100}, 34.0 * M_PI / 180.0), 10.0f);
}

TEST(OrientedDistanceMap, HalfResolutionKeepsDistancesInFullResolutionPixels) {
  const OrientedDistanceMap map = horizontalAt100(2);
  EXPECT_NEAR(map.distance({200, 108}, kHorizontal), 8.0, 1.0);
}

TEST(OrientedDistanceMap, OutsideTheImageShortSegmentsAndNaNGiveTheTruncation) {
  const OrientedDistanceMap map = horizontalAt100(1);
  EXPECT_FLOAT_EQ(map.distance({-1, 100}, kHorizontal), 10.0f);
  EXPECT_FLOAT_EQ(map.distance({640, 100}, kHorizontal), 10.0f);
  EXPECT_FLOAT_EQ(map.distance({std::nan(""), 100}, kHorizontal), 10.0f);
  EXPECT_FLOAT_EQ(map.distance({1e300, 100}, kHorizontal), 10.0f);
  const OrientedDistanceMap short_only({segment(100, 100, 110, 100)}, 640, 480, {15.0, 10.0, 1});
  EXPECT_FLOAT_EQ(short_only.distance({105, 100}, kHorizontal), 10.0f);
}

TEST(OrientedDistanceMap, CoveredLengthIsTheLengthWeightedByOneMinusTheMeanDistance) {
  const OrientedDistanceMap map = horizontalAt100(1);
  // On the segment: fully covered; 6 px beside it: 1 - 6/10 of the length;
  // 20 px away or across it: nothing.
  EXPECT_NEAR(map.coveredLength({120, 100}, {280, 100}, 6.0), 160.0, 1e-6);
  EXPECT_NEAR(map.coveredLength({280, 100}, {120, 100}, 6.0), 160.0, 1e-6);
  EXPECT_NEAR(map.coveredLength({120, 106}, {280, 106}, 6.0), 0.4 * 160.0, 1e-3);
  EXPECT_NEAR(map.coveredLength({120, 120}, {280, 120}, 6.0), 0.0, 1e-6);
  EXPECT_NEAR(map.coveredLength({200, 20}, {200, 180}, 6.0), 0.0, 1e-6);
  // Half on the segment, half beyond its end: half covered, give or take the
  // distance ramp past the end.
  EXPECT_NEAR(map.coveredLength({200, 100}, {400, 100}, 4.0), 100.0 + 0.5 * 10.0, 4.0);
  // Shorter than one sample spacing: nothing to sample.
  EXPECT_EQ(map.coveredLength({120, 100}, {125, 100}, 6.0), 0.0);
  // Half resolution measures the same.
  EXPECT_NEAR(horizontalAt100(2).coveredLength({120, 100}, {280, 100}, 6.0), 160.0, 1e-6);
}

TEST(OrientedDistanceMap, BinsWrapAroundHalfATurn) {
  EXPECT_EQ(OrientedDistanceMap::binOf(0.0), 0);
  EXPECT_EQ(OrientedDistanceMap::binOf(M_PI), 0);
  EXPECT_EQ(OrientedDistanceMap::binOf(-M_PI / 8.0), OrientedDistanceMap::kOrientationBins - 1);
  EXPECT_EQ(OrientedDistanceMap::binOf(M_PI / 2.0), OrientedDistanceMap::kOrientationBins / 2);
}

}  // namespace
}  // namespace lineloc
