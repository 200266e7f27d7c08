// Scalar reference of the SAD kernels: the definition, one pixel at a time.
// Compiled without auto-vectorisation so that it stays the scalar baseline.
#include <algorithm>
#include <cstdlib>

#include "robot/vision/block_matching/disparity_kernel_loops.h"
#include "robot/vision/block_matching/sad_paths.h"

namespace lineloc::sad_paths {
namespace {

uint32_t sad(const uint8_t* a, ptrdiff_t a_stride, const uint8_t* b, ptrdiff_t b_stride, int width,
             int height) {
  uint32_t sum = 0;
  for (int r = 0; r < height; ++r, a += a_stride, b += b_stride) {
    for (int c = 0; c < width; ++c) {
      sum += static_cast<uint32_t>(std::abs(a[c] - b[c]));
    }
  }
  return sum;
}

// One function per block size, with constant loop bounds (the inner loop
// unrolled); kept out of line so that it stays so inside the search loops.
template <int kWidth, int kHeight>
[[gnu::noinline]] uint32_t fixedSizeSad(const uint8_t* a, ptrdiff_t a_stride, const uint8_t* b,
                                        ptrdiff_t b_stride) {
  return sad(a, a_stride, b, b_stride, kWidth, kHeight);
}

template <int kWidth, int kHeight>
void gridFullSearchOf(const GridSearch& search, BlockBest* best) {
  const int radius = search.radius_px;
  for (int y = 0; y + kHeight <= search.height_px; y += kHeight) {
    for (int x = 0; x + kWidth <= search.width_px; x += kWidth, ++best) {
      const uint8_t* block = search.reference + y * search.stride + x;
      uint64_t best_rank = UINT64_MAX;
      for (int dy = std::max(-radius, -y); dy <= std::min(radius, search.height_px - kHeight - y);
           ++dy) {
        for (int dx = std::max(-radius, -x); dx <= std::min(radius, search.width_px - kWidth - x);
             ++dx) {
          const uint8_t* candidate = search.current + (y + dy) * search.stride + x + dx;
          const uint32_t sum =
              fixedSizeSad<kWidth, kHeight>(block, search.stride, candidate, search.stride);
          const uint64_t rank = candidateRank(sum, dx, dy);
          if (rank < best_rank) {
            best_rank = rank;
            *best = {sum, dx, dy};
          }
        }
      }
    }
  }
}

void gridFullSearch(const GridSearch& search, BlockBest* best) {
  const int w = search.block_width_px, h = search.block_height_px;
  if (w == 16 && h == 16) {
    gridFullSearchOf<16, 16>(search, best);
  } else if (w == 16) {
    gridFullSearchOf<16, 8>(search, best);
  } else if (h == 16) {
    gridFullSearchOf<8, 16>(search, best);
  } else {
    gridFullSearchOf<8, 8>(search, best);
  }
}

}  // namespace

const SadKernels& scalarKernels() {
  static const SadKernels kernels{SimdPath::kScalar,
                                  fixedSizeSad<16, 16>,
                                  fixedSizeSad<8, 8>,
                                  sad,
                                  gridFullSearch,
                                  DisparityLoops<uint16_t>::table(),
                                  DisparityLoops<uint32_t>::table(),
                                  nullptr};
  return kernels;
}

}  // namespace lineloc::sad_paths
