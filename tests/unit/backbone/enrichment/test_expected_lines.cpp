// A known line in view of enough precisely placed frames is expected; one a
// face hides, one out of view, and one seen from imprecise poses are not.
#include <gtest/gtest.h>

#include "backbone/enrichment/expected_lines.h"
#include "wall_drive.h"

namespace lineloc {
namespace {

using namespace wall_drive;

const Plane kWall{-Eigen::Vector3d::UnitX(), -kWall_x};

std::vector<KnownLearntLine> knownLines() {
  return {{1, kWindowSideStart, kWindowSideEnd, kWall},
          // Behind a hoarding at x = 8 in front of the wall, y 6..11.
          {2, {kWall_x, 8.0, 1.5}, {kWall_x, 9.0, 1.5}, kWall},
          // Far along the wall, out of every view.
          {3, {kWall_x, 60.0, 1.5}, {kWall_x, 61.0, 1.5}, kWall}};
}

std::vector<FaceRing> wallAndHoarding() {
  std::vector<FaceRing> faces = wallFaces();
  faces.push_back({{8.0, 11.0, 0.0}, {8.0, 6.0, 0.0}, {8.0, 6.0, 4.0}, {8.0, 11.0, 4.0}});
  return faces;
}

TEST(ExpectedLines, OnlyALineInViewOfEnoughPreciseFramesIsExpected) {
  const OcclusionScene scene(wallAndHoarding(), {kBuilding, kBuilding + 1});
  ExpectedLines lines(knownLines(), ExpectedLineOptions{});
  std::mt19937 random(3);
  for (int k = 0; k < 12; ++k) {
    EnrichmentFrame frame = frameAt(cameraAt(0.5 * k), 0.0, random);
    frame.stamp_ns = 1'000'000'000LL * k;
    lines.observe(frame, scene);
  }
  const std::vector<ExpectedLine> expected = lines.expected();
  ASSERT_EQ(expected.size(), 1u);
  EXPECT_EQ(expected[0].id, 1);
  EXPECT_EQ(expected[0].expected_at_ns, 11'000'000'000LL);

  // Without the hoarding the line behind it is in view too.
  const OcclusionScene open(wallFaces(), {kBuilding});
  ExpectedLines unhidden(knownLines(), ExpectedLineOptions{});
  for (int k = 0; k < 12; ++k) {
    unhidden.observe(frameAt(cameraAt(0.5 * k), 0.0, random), open);
  }
  ASSERT_EQ(unhidden.expected().size(), 2u);
  EXPECT_EQ(unhidden.expected()[1].id, 2);
}

TEST(ExpectedLines, TooFewOrImpreciseFramesExpectNothing) {
  const OcclusionScene scene(wallAndHoarding(), {kBuilding, kBuilding + 1});
  std::mt19937 random(3);
  ExpectedLines few(knownLines(), ExpectedLineOptions{});
  for (int k = 0; k < 9; ++k) {
    few.observe(frameAt(cameraAt(0.5 * k), 0.0, random), scene);
  }
  EXPECT_TRUE(few.expected().empty());
  ExpectedLines imprecise(knownLines(), ExpectedLineOptions{});
  for (int k = 0; k < 12; ++k) {
    PoseWithCovariance pose = cameraAt(0.5 * k);
    pose.covariance = diagonalPoseCovariance(0.3, 0.001);
    imprecise.observe(frameAt(pose, 0.0, random), scene);
  }
  EXPECT_TRUE(imprecise.expected().empty());
}

}  // namespace
}  // namespace lineloc
