// Disparity-space kernels of the SAD stereo matcher (stereo/sad_stereo_matcher.h):
// the cost volume is kept as one row of costs per disparity with x
// contiguous, so that every step is a pass along x that each SIMD path runs
// on whole registers:
//
//   column sums   C_d(x) = sum_{rows j of the block} |L(x, j) - R(x - d, j)|,
//                 slid down one image row at a time (add the new row,
//                 subtract the one that left the block);
//   block costs   S_d(x) = sum_{|i| <= h} C_d(x + i), by power-of-two
//                 partial sums (about log2(2h + 1) passes instead of 2h + 1);
//   winners       the running minimum over d of S_d(x) per x with its index
//                 and the costs at the index -1 and +1 (for the sub-pixel
//                 fit), then the costs within the uniqueness margin; and per
//                 right-image pixel xr the minimum over d of S_d(xr + d) (for
//                 the left-right check).
//
// Arrays passed to one call do not overlap. Cost is uint16_t where the largest block cost fits 16
// bits, uint32_t otherwise; kNoCost<Cost> (all bits set) marks a disparity whose block leaves an
// image.
#pragma once

#include <cstdint>
#include <limits>

namespace lineloc {

template <typename Cost>
inline constexpr Cost kNoCost = std::numeric_limits<Cost>::max();

template <typename Cost>
struct DisparityKernels {
  // columns[x] += |left[x] - right[x]|, x < count.
  void (*addRow)(const uint8_t* left, const uint8_t* right, int count, Cost* columns);
  // columns[x] += |left_in[x] - right_in[x]| - |left_out[x] - right_out[x]|.
  void (*slideRow)(const uint8_t* left_in, const uint8_t* right_in, const uint8_t* left_out,
                   const uint8_t* right_out, int count, Cost* columns);
  // sums[x] = columns[x] + ... + columns[x + window - 1] for
  // x <= count - window (1 <= window <= count); `scratch` holds 2 count.
  void (*windowSums)(const Cost* columns, int count, int window, Cost* sums, Cost* scratch);
  // Disparity index k with costs S_k(x) (previous: S_{k-1}, all kNoCost for
  // k = 0) into the running minimum of x < count: where costs[x] < best[x],
  // best = costs, index = k, minus = previous; where index was k - 1 before,
  // plus = costs. Start from best = kNoCost.
  void (*considerDisparity)(const Cost* costs, const Cost* previous, Cost k, int count, Cost* best,
                            Cost* index, Cost* minus, Cost* plus);
  // ambiguous[x] |= costs[x] <= limit[x] and |k - index[x]| > 1, x < count.
  void (*markAmbiguous)(const Cost* costs, const Cost* limit, const Cost* index, Cost k, int count,
                        uint8_t* ambiguous);
  // Running minimum for the right image: where costs[x] < best[x],
  // best = costs and index = k, x < count.
  void (*considerRight)(const Cost* costs, Cost k, int count, Cost* best, Cost* index);
  // limit[x] = min(floor(best[x] factor / 100), kNoCost - 1): the largest
  // cost within (factor - 100) percent of the best; factor <= 1100.
  void (*uniquenessLimits)(const Cost* best, int factor, int count, Cost* limit);
  // Winners into disparities: valid[x] = 255 and disparity[x] =
  // first_disparity + index + the equiangular offset (Shimizu & Okutomi 2001,
  // exact for the SAD of a locally linear signal)
  //
  //   offset = clamp((minus - plus) / (2 (max(minus, plus) - best)), -1/2, 1/2)
  //
  // where the winner is neither the first (index 0) nor the last disparity,
  // not ambiguous, and the cost rises on both sides; valid = 0 and
  // disparity = 0 elsewhere.
  void (*subpixelWinners)(const Cost* best, const Cost* index, const Cost* minus, const Cost* plus,
                          const uint8_t* ambiguous, int first_disparity, int last_index, int count,
                          float* disparity, uint8_t* valid);
};

}  // namespace lineloc
