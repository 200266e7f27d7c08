// Brick courses repeat and are dropped; a window frame's outer and inner
// edges, bright on opposite sides, and the tops of windows side by side stay.
#include <gtest/gtest.h>

#include "backbone/enrichment/repeated_lines.h"

namespace lineloc {
namespace {

// A horizontal line on the wall x = 10 at height z from y0 to y1, bright
// above (+1) or below (-1).
LineCandidate onWall(double z, double y0, double y1, double bright) {
  LineCandidate learnt;
  learnt.building_id = 3;
  learnt.plane = {Eigen::Vector3d(-1, 0, 0), -10.0};
  learnt.line.start_world = {10.0, y0, z};
  learnt.line.end_world = {10.0, y1, z};
  learnt.line.direction = Eigen::Vector3d::UnitY();
  learnt.brighter_side = Eigen::Vector3d(0, 0, bright);
  return learnt;
}

TEST(RepeatedLines, BrickCoursesGoWindowEdgesStay) {
  std::vector<LineCandidate> candidates;
  for (int course = 0; course < 5; ++course) {
    candidates.push_back(onWall(1.0 + 0.075 * course, 0.0, 3.0, 1.0));
  }
  const std::vector<LineCandidate> window = {
      onWall(3.50, 5.0, 6.2, -1.0),   // the frame's outer top, the frame below it
      onWall(3.42, 5.08, 6.12, 1.0),  // its inner top, the frame above it
      onWall(3.50, 7.6, 8.8, -1.0),   // the next window's top, in line but apart
  };
  candidates.insert(candidates.end(), window.begin(), window.end());
  const std::vector<LineCandidate> kept = withoutRepeatedLines(candidates);
  ASSERT_EQ(kept.size(), 3u);
  for (size_t i = 0; i < kept.size(); ++i) {
    EXPECT_EQ(kept[i].line.start_world, window[i].line.start_world);
  }
}

TEST(RepeatedLines, LinesOnOtherWallsOrBuildingsDoNotRepeat) {
  LineCandidate a = onWall(1.0, 0.0, 3.0, 1.0);
  LineCandidate b = onWall(1.05, 0.0, 3.0, 1.0);
  b.building_id = 4;
  EXPECT_EQ(withoutRepeatedLines({a, b}).size(), 2u);
  b.building_id = a.building_id;
  b.plane.normal = Eigen::Vector3d(0, -1, 0);
  EXPECT_EQ(withoutRepeatedLines({a, b}).size(), 2u);
}

}  // namespace
}  // namespace lineloc
