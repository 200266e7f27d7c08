#include "robot/vision/edges/neighbour_steps.h"

namespace lineloc {

NeighbourSteps::NeighbourSteps() {
  for (int direction = 0; direction < kDirections; ++direction) {
    for (unsigned occupied = 0; occupied < kMasks; ++occupied) {
      table_[direction * kMasks + occupied] = tabulate(direction, occupied);
    }
  }
}

NeighbourSteps::Choice NeighbourSteps::tabulate(int direction, unsigned occupied) {
  const double angle = (direction + 0.5) * 2.0 * M_PI / kDirections;
  const double tx = std::cos(angle), ty = std::sin(angle);
  Choice choice{kNone, kNone};
  double best_length[2] = {0.0, 0.0}, best_alignment[2] = {0.0, 0.0};
  for (int k = 0; k < 8; ++k) {
    if (!(occupied & (1u << k))) {
      continue;
    }
    const NeighbourStep& step = kNeighbourSteps[k];
    const double length = std::hypot(step.dx, step.dy);
    const double along = step.dx * tx + step.dy * ty;
    const int side = along > 0.0 ? 0 : 1;
    uint8_t& chosen = side == 0 ? choice.ahead : choice.behind;
    const double alignment = std::abs(along) / length;
    if (chosen == kNone || length < best_length[side] ||
        (length == best_length[side] && alignment > best_alignment[side])) {
      chosen = static_cast<uint8_t>(k);
      best_length[side] = length;
      best_alignment[side] = alignment;
    }
  }
  return choice;
}

}  // namespace lineloc
