#include "robot/vision/block_matching/candidate_rank.h"

#include <cstddef>

namespace lineloc {

// Counting sort by dx^2 + dy^2; within one length the row-major scan already
// visits (dy, dx) in increasing order.
std::vector<uint16_t> tieOrder(int radius_px) {
  const int side = 2 * radius_px + 1;
  std::vector<int> next(2 * radius_px * radius_px + 2, 0);
  for (int dy = -radius_px; dy <= radius_px; ++dy) {
    for (int dx = -radius_px; dx <= radius_px; ++dx) {
      ++next[dx * dx + dy * dy + 1];
    }
  }
  for (size_t length2 = 1; length2 < next.size(); ++length2) {
    next[length2] += next[length2 - 1];
  }
  std::vector<uint16_t> order(static_cast<size_t>(side) * side);
  for (int dy = -radius_px; dy <= radius_px; ++dy) {
    for (int dx = -radius_px; dx <= radius_px; ++dx) {
      order[(dy + radius_px) * side + dx + radius_px] =
          static_cast<uint16_t>(next[dx * dx + dy * dy]++);
    }
  }
  return order;
}

}  // namespace lineloc
