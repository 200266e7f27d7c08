#include "robot/vision/edges/edge_linker.h"

#include <cmath>
#include <stdexcept>

namespace lineloc {
EdgeLinker::EdgeLinker(const EdgeLinkerOptions& options)
    : options_(options), cos_max_turn_(static_cast<float>(std::cos(options.max_turn_rad))) {
  if (!(options.max_turn_rad > 0.0 && options.max_turn_rad < M_PI) || options.min_points < 2) {
    throw std::invalid_argument("edge linker: max_turn_rad must be in (0, pi), min_points >= 2");
  }
}

void EdgeLinker::link(const std::vector<EdgePoint>& points) {
  const int32_t count = static_cast<int32_t>(points.size());
  next_.assign(count, -1);
  previous_.assign(count, -1);
  for (int32_t p = 0; p < count; ++p) {
    const int32_t q = points[p].ahead;
    if (q >= 0 && points[q].behind == p &&
        points[q].normal.dot(points[p].normal) >= cos_max_turn_) {
      next_[p] = q;
      previous_[q] = p;
    }
  }
  visited_.assign(count, 0);
  chain_points_.clear();
  chains_.clear();
  for (int32_t p = 0; p < count; ++p) {
    if (previous_[p] < 0) {
      addChain(p);
    }
  }
  for (int32_t p = 0; p < count; ++p) {
    if (!visited_[p]) {
      addChain(p);
    }
  }
}

void EdgeLinker::addChain(int32_t first) {
  const int begin = static_cast<int>(chain_points_.size());
  for (int32_t p = first; p >= 0 && !visited_[p]; p = next_[p]) {
    visited_[p] = 1;
    chain_points_.push_back(p);
  }
  const PointRange chain{begin, static_cast<int>(chain_points_.size())};
  if (chain.size() >= options_.min_points) {
    chains_.push_back(chain);
  } else {
    chain_points_.resize(begin);
  }
}

}  // namespace lineloc
