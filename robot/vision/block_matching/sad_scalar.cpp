// Scalar reference of the SAD kernels: the definition, one pixel at a time.
// Compiled without auto-vectorisation so that it stays the scalar baseline.
#include <cstdlib>

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

uint32_t sad16x16(const uint8_t* a, ptrdiff_t a_stride, const uint8_t* b, ptrdiff_t b_stride) {
  return sad(a, a_stride, b, b_stride, 16, 16);
}

uint32_t sad8x8(const uint8_t* a, ptrdiff_t a_stride, const uint8_t* b, ptrdiff_t b_stride) {
  return sad(a, a_stride, b, b_stride, 8, 8);
}

void sadColumn16x16(const uint8_t* block, ptrdiff_t block_stride, const uint8_t* candidates,
                    ptrdiff_t stride, int count, uint32_t* sads) {
  for (int k = 0; k < count; ++k) {
    sads[k] = sad16x16(block, block_stride, candidates + k * stride, stride);
  }
}

void absDiffRow(const uint8_t* a, const uint8_t* b, int width, uint8_t* out) {
  for (int i = 0; i < width; ++i) {
    out[i] = static_cast<uint8_t>(std::abs(a[i] - b[i]));
  }
}

}  // namespace

const SadKernels& scalarKernels() {
  static const SadKernels kernels{SimdPath::kScalar, sad16x16,   sad8x8, sad,
                                  sadColumn16x16,    absDiffRow, nullptr};
  return kernels;
}

}  // namespace lineloc::sad_paths
