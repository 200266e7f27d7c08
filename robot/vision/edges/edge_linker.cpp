#include "robot/vision/edges/edge_linker.h"

#include <stdexcept>

namespace lineloc {
EdgeLinker::EdgeLinker(const EdgeLinkerOptions& options) : options_(options) {
  if (options.min_points < 2) {
    throw std::invalid_argument("edge linker: min_points must be >= 2");
  }
}

void EdgeLinker::link(const std::vector<int32_t>& next, const std::vector<int32_t>& previous) {
  const int32_t count = static_cast<int32_t>(next.size());
  visited_.assign(count, 0);
  chain_points_.clear();
  chains_.clear();
  for (int32_t p = 0; p < count; ++p) {
    if (previous[p] < 0) {
      addChain(next, p);
    }
  }
  for (int32_t p = 0; p < count; ++p) {
    if (!visited_[p]) {
      addChain(next, p);
    }
  }
}

void EdgeLinker::addChain(const std::vector<int32_t>& next, int32_t first) {
  const int begin = static_cast<int>(chain_points_.size());
  int32_t p = first;
  do {
    visited_[p] = 1;
    chain_points_.push_back(p);
    p = next[p] >= 0 && !visited_[next[p]] ? next[p] : -1;
  } while (p >= 0);
  const PointRange chain{begin, static_cast<int>(chain_points_.size())};
  if (chain.size() >= options_.min_points) {
    chains_.push_back(chain);
  } else {
    chain_points_.resize(begin);
  }
}

}  // namespace lineloc
