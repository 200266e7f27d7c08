#include "robot/vision/edges/neighbour_steps.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lineloc {
namespace {

unsigned bitOf(int dx, int dy) {
  for (int k = 0; k < 8; ++k) {
    if (kNeighbourSteps[k].dx == dx && kNeighbourSteps[k].dy == dy) {
      return 1u << k;
    }
  }
  ADD_FAILURE() << "no step " << dx << "," << dy;
  return 0;
}

NeighbourStep stepOf(uint8_t k) {
  return k == NeighbourSteps::kNone ? NeighbourStep{0, 0} : kNeighbourSteps[k];
}

void expectStep(uint8_t k, int dx, int dy) {
  const NeighbourStep step = stepOf(k);
  EXPECT_EQ(step.dx, dx);
  EXPECT_EQ(step.dy, dy);
}

TEST(NeighbourSteps, FollowsAStraightEdgeBothWays) {
  const NeighbourSteps steps;
  // Tangent along +x, 10 degrees off: ahead is +x, behind is -x.
  const double a = 10.0 * M_PI / 180.0;
  const auto choice = steps.choose(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)),
                                   bitOf(1, 0) | bitOf(-1, 0));
  expectStep(choice.ahead, 1, 0);
  expectStep(choice.behind, -1, 0);
}

TEST(NeighbourSteps, ReportsAVacantSide) {
  const NeighbourSteps steps;
  const auto choice = steps.choose(0.0f, 1.0f, bitOf(0, 1));
  expectStep(choice.ahead, 0, 1);
  EXPECT_EQ(choice.behind, NeighbourSteps::kNone);
  EXPECT_EQ(steps.choose(0.0f, 1.0f, 0).ahead, NeighbourSteps::kNone);
}

// A 45 degree edge leaves pairs of pixels side by side: the chain goes to the
// partner first (1 px), not the diagonal (1.4 px), so it holds every point.
TEST(NeighbourSteps, WalksThroughBothPixelsOfAStaircase) {
  const NeighbourSteps steps;
  const float t = static_cast<float>(M_SQRT1_2);
  expectStep(steps.choose(t, t, bitOf(1, 0) | bitOf(1, 1) | bitOf(-1, -1)).ahead, 1, 0);
  expectStep(steps.choose(t, t, bitOf(0, 1) | bitOf(1, 1) | bitOf(-1, 0)).ahead, 0, 1);
}

// Two neighbours as near: the one more nearly along the tangent.
TEST(NeighbourSteps, BreaksATieTowardsTheTangent) {
  const NeighbourSteps steps;
  const double a = 30.0 * M_PI / 180.0;  // nearer +x than +y
  expectStep(steps
                 .choose(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)),
                         bitOf(1, 0) | bitOf(0, 1))
                 .ahead,
             1, 0);
  const double b = 60.0 * M_PI / 180.0;  // nearer +y
  expectStep(steps
                 .choose(static_cast<float>(std::cos(b)), static_cast<float>(std::sin(b)),
                         bitOf(1, 0) | bitOf(0, 1))
                 .ahead,
             0, 1);
}

// The tangent's direction is found in every quadrant: a step straight along
// it is chosen ahead and its opposite behind, at every degree.
TEST(NeighbourSteps, FindsTheDirectionAllAround) {
  const NeighbourSteps steps;
  for (int degrees = 0; degrees < 360; ++degrees) {
    const double a = degrees * M_PI / 180.0;
    const float tx = static_cast<float>(std::cos(a)), ty = static_cast<float>(std::sin(a));
    const int sx = std::abs(tx) < 0.38f ? 0 : (tx > 0 ? 1 : -1);
    const int sy = std::abs(ty) < 0.38f ? 0 : (ty > 0 ? 1 : -1);
    const auto choice = steps.choose(tx, ty, bitOf(sx, sy) | bitOf(-sx, -sy));
    expectStep(choice.ahead, sx, sy);
    expectStep(choice.behind, -sx, -sy);
  }
}

}  // namespace
}  // namespace lineloc
