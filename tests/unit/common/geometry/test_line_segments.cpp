#include <gtest/gtest.h>

#include <cmath>

#include "common/geometry/line_segments.h"

namespace lineloc {
namespace {

TEST(LineSegments, DistanceIsToTheNearestPointOfTheSegment) {
  const Eigen::Vector2d a(0, 0), b(4, 0);
  EXPECT_DOUBLE_EQ(distanceToSegment<2>({2, 3}, a, b), 3.0);
  EXPECT_DOUBLE_EQ(distanceToSegment<2>({7, 4}, a, b), 5.0);
  EXPECT_DOUBLE_EQ(distanceToSegment<2>({-1, 0}, a, a), 1.0);
}

TEST(LineSegments, DistanceToAPolylineIsToItsNearestSegment) {
  const std::vector<Eigen::Vector2d> corner = {{0, 0}, {10, 0}, {10, 10}};
  EXPECT_DOUBLE_EQ(distanceToPolyline({5, 2}, corner), 2.0);
  EXPECT_DOUBLE_EQ(distanceToPolyline({12, 5}, corner), 2.0);
  EXPECT_DOUBLE_EQ(distanceToPolyline({13, -4}, corner), 5.0);
  EXPECT_DOUBLE_EQ(distanceToPolyline({3, 4}, {{0, 0}}), 5.0);
  EXPECT_EQ(distanceToPolyline({3, 4}, {}), std::numeric_limits<double>::infinity());
}

TEST(LineSegments, ASegmentRunsAlongAnotherParallelCloseAndOverlapping) {
  const Eigen::Vector3d a0(0, 0, 0), a1(10, 0, 0);
  const double angle = 3.0 * M_PI / 180.0;
  EXPECT_TRUE(runsAlong(a0, a1, {2, 0.04, 0}, {5, 0.03, 0}, angle, 0.05));
  EXPECT_TRUE(runsAlong(a0, a1, {12, 0, 0}, {8, 0, 0}, angle, 0.05));     // reversed, overlapping
  EXPECT_FALSE(runsAlong(a0, a1, {2, 0.06, 0}, {5, 0, 0}, angle, 0.05));  // an end too far
  EXPECT_FALSE(runsAlong(a0, a1, {11, 0, 0}, {14, 0, 0}, angle, 0.05));   // past its end
  EXPECT_FALSE(runsAlong(a0, a1, {2, 0, 0}, {5, 0.3, 0}, angle, 0.5));    // 5.7 degrees off
  EXPECT_FALSE(runsAlong(a0, a0, {0, 0, 0}, {1, 0, 0}, angle, 0.05));     // a of no length
}

}  // namespace
}  // namespace lineloc
