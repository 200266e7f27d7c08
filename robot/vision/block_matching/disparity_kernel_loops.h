// Internal: the disparity kernels (disparity_kernels.h) as plain loops along
// x over contiguous rows, written once and compiled in every instruction-set
// translation unit: the vector units' flags let the compiler run each loop on
// whole registers, the scalar reference's unit is compiled without
// vectorisation. Integer arithmetic only, so every path gives the same
// results. Internal linkage for the reason given in sad_vector_kernels.h.
#pragma once

#include <algorithm>
#include <cmath>

#include "robot/vision/block_matching/disparity_kernels.h"

namespace lineloc::sad_paths {
namespace {

template <typename Cost>
struct DisparityLoops {
  static Cost absDiff(uint8_t a, uint8_t b) { return static_cast<Cost>(a > b ? a - b : b - a); }

  static void addRow(const uint8_t* __restrict left, const uint8_t* __restrict right, int count,
                     Cost* __restrict columns) {
    for (int x = 0; x < count; ++x) {
      columns[x] = static_cast<Cost>(columns[x] + absDiff(left[x], right[x]));
    }
  }

  static void slideRow(const uint8_t* __restrict left_in, const uint8_t* __restrict right_in,
                       const uint8_t* __restrict left_out, const uint8_t* __restrict right_out,
                       int count, Cost* __restrict columns) {
    for (int x = 0; x < count; ++x) {
      columns[x] = static_cast<Cost>(columns[x] + absDiff(left_in[x], right_in[x]) -
                                     absDiff(left_out[x], right_out[x]));
    }
  }

  // With p_w(x) = columns[x] + ... + columns[x + w - 1]: sums = the sum of
  // p_b(x + offset_b) over the set bits b of window, offset_b the sum of the
  // lower set bits; p_2w(x) = p_w(x) + p_w(x + w).
  static void windowSums(const Cost* columns, int count, int window, Cost* sums, Cost* scratch) {
    const int outputs = count - window + 1;
    const Cost* partial = columns;
    Cost* doubled = scratch;
    Cost* spare = scratch + count;
    int length = count;  // of partial
    int offset = 0;
    bool started = false;
    for (int width = 1; width <= window; width *= 2) {
      if (window & width) {
        accumulate(partial + offset, outputs, started, sums);
        started = true;
        offset += width;
      }
      if (2 * width > window) {
        break;
      }
      length -= width;
      doublePartials(partial, width, length, doubled);
      partial = doubled;
      std::swap(doubled, spare);
    }
  }

  static void doublePartials(const Cost* __restrict partial, int width, int length,
                             Cost* __restrict doubled) {
    for (int x = 0; x < length; ++x) {
      doubled[x] = static_cast<Cost>(partial[x] + partial[x + width]);
    }
  }

  static void accumulate(const Cost* __restrict values, int count, bool add,
                         Cost* __restrict sums) {
    if (add) {
      for (int x = 0; x < count; ++x) {
        sums[x] = static_cast<Cost>(sums[x] + values[x]);
      }
    } else {
      std::copy(values, values + count, sums);
    }
  }

  static void considerDisparity(const Cost* __restrict costs, const Cost* __restrict previous,
                                Cost k, int count, Cost* __restrict best, Cost* __restrict index,
                                Cost* __restrict minus, Cost* __restrict plus) {
    const Cost k_before = static_cast<Cost>(k - 1);
    for (int x = 0; x < count; ++x) {
      const Cost cost = costs[x];
      const bool better = cost < best[x];
      plus[x] = index[x] == k_before ? cost : plus[x];
      minus[x] = better ? previous[x] : minus[x];
      best[x] = better ? cost : best[x];
      index[x] = better ? k : index[x];
    }
  }

  static void markAmbiguous(const Cost* __restrict costs, const Cost* __restrict limit,
                            const Cost* __restrict index, Cost k, int count,
                            uint8_t* __restrict ambiguous) {
    for (int x = 0; x < count; ++x) {
      const bool far = k > index[x] + 1 || k + 1 < index[x];
      ambiguous[x] |= static_cast<uint8_t>(far && costs[x] <= limit[x]);
    }
  }

  static void considerRight(const Cost* __restrict costs, Cost k, int count, Cost* __restrict best,
                            Cost* __restrict index) {
    for (int x = 0; x < count; ++x) {
      const bool better = costs[x] < best[x];
      best[x] = better ? costs[x] : best[x];
      index[x] = better ? k : index[x];
    }
  }

  // floor(b f / 100) in double is exact: b f < 2^32 * 1100 < 2^53.
  static void uniquenessLimits(const Cost* __restrict best, int factor, int count,
                               Cost* __restrict limit) {
    const double largest = static_cast<double>(kNoCost<Cost> - 1);
    for (int x = 0; x < count; ++x) {
      const double within = std::floor(static_cast<double>(best[x]) * factor / 100.0);
      limit[x] = static_cast<Cost>(std::min(within, largest));
    }
  }

  static void subpixelWinners(const Cost* __restrict best, const Cost* __restrict index,
                              const Cost* __restrict minus, const Cost* __restrict plus,
                              const uint8_t* __restrict ambiguous, int first_disparity,
                              int last_index, int count, float* __restrict disparity,
                              uint8_t* __restrict valid) {
    const Cost last = static_cast<Cost>(last_index);
    for (int x = 0; x < count; ++x) {
      const double rise = static_cast<double>(std::max(minus[x], plus[x])) - best[x];
      const bool chosen = best[x] != kNoCost<Cost> && index[x] != 0 && index[x] != last &&
                          plus[x] != kNoCost<Cost> && !ambiguous[x] && rise > 0.0;
      const double slope =
          (static_cast<double>(minus[x]) - plus[x]) / (2.0 * (chosen ? rise : 1.0));
      const float offset = static_cast<float>(std::clamp(slope, -0.5, 0.5));
      disparity[x] =
          chosen ? static_cast<float>(first_disparity + static_cast<int>(index[x])) + offset : 0.0f;
      valid[x] = chosen ? 255 : 0;
    }
  }

  static DisparityKernels<Cost> table() {
    return {addRow,        slideRow,      windowSums,       considerDisparity,
            markAmbiguous, considerRight, uniquenessLimits, subpixelWinners};
  }
};

}  // namespace
}  // namespace lineloc::sad_paths
