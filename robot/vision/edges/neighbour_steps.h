// Which 8-neighbour continues an edge: given the edge tangent t at a pixel
// and which of its 8 neighbours hold edge points, the nearest of those ahead
// of it (step s with s.t > 0) and the nearest behind (s.t < 0), a tie going
// to the step more nearly along t. The nearest wins so that a chain runs
// through both pixels of the two-pixel-wide staircase non-maximum suppression
// leaves along slanted edges. t is quantised to 16 directions, 22.5 degrees
// apart, none of whose centres is perpendicular to a step; all 16 x 256
// answers are tabulated once, on construction.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace lineloc {

struct NeighbourStep {
  int dx, dy;
};

// The 8 neighbours in raster order; bit k of an occupancy mask is step k.
inline constexpr NeighbourStep kNeighbourSteps[8] = {{-1, -1}, {0, -1}, {1, -1}, {-1, 0},
                                                     {1, 0},   {-1, 1}, {0, 1},  {1, 1}};

class NeighbourSteps {
 public:
  static constexpr int kNone = 8;  // no neighbour on that side

  struct Choice {
    uint8_t ahead;   // index in kNeighbourSteps, or kNone
    uint8_t behind;  // index in kNeighbourSteps, or kNone
  };

  NeighbourSteps();

  // `tangent_x`, `tangent_y`: t (any length > 0); `occupied`: 8-bit mask.
  Choice choose(float tangent_x, float tangent_y, unsigned occupied) const {
    return table_[directionOf(tangent_x, tangent_y) * kMasks + (occupied & (kMasks - 1))];
  }

 private:
  static constexpr int kDirections = 16;
  static constexpr int kMasks = 256;

  // The 22.5 degree sector holding the angle of t, counter-clockwise from +x:
  // the quadrant from the signs, then |t| rotated into the first quadrant
  // against tan 22.5, tan 45 and tan 67.5 degrees; no branches.
  static int directionOf(float tx, float ty) {
    constexpr float kTan22_5Deg = 0.41421356f;
    constexpr float kTan67_5Deg = 2.41421356f;
    const int negative_x = tx < 0.0f;
    const int negative_y = ty < 0.0f;
    const int quadrant = 2 * negative_y + (negative_x ^ negative_y);
    const float ax = std::abs(tx), ay = std::abs(ty);
    const float u = quadrant & 1 ? ay : ax;
    const float v = quadrant & 1 ? ax : ay;
    return 4 * quadrant + (v > kTan22_5Deg * u) + (v > u) + (v > kTan67_5Deg * u);
  }

  static Choice tabulate(int direction, unsigned occupied);

  std::array<Choice, kDirections * kMasks> table_;
};

}  // namespace lineloc
