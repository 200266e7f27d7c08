// Nearest-rank percentiles of latencies and other samples: the value at rank
// ceil(p / 100 * n) (1-based) of the n sorted samples, for p in [0, 100].
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace lineloc {

// 0 (a value-initialised T) for no samples.
template <typename T>
T percentile(std::vector<T> values, double percent) {
  if (values.empty()) {
    return T{};
  }
  const size_t rank = static_cast<size_t>(std::ceil(percent / 100.0 * values.size()));
  const size_t index = std::clamp<size_t>(rank, 1, values.size()) - 1;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index),
                   values.end());
  return values[index];
}

}  // namespace lineloc
