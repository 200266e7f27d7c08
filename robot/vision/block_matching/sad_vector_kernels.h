// Internal: the SAD kernels written once over a vector "traits" type, and
// instantiated in each instruction-set translation unit (sad_sse2.cpp,
// sad_avx2.cpp, sad_avx512bw.cpp) with that unit's traits.
//
// Everything here has internal linkage, so each unit keeps its own copy
// compiled with its own target flags (a shared inline function could be
// merged by the linker into the widest unit's code and run on a processor
// without that instruction set).
//
// Traits V provide: kBytes (register width), Reg, zero(), load(p), store(p, x),
// add64(x, y), sad(x, y) (`psadbw`: per 8-byte group, the u64 sum of
// |x - y|), loadRows16(p, stride)
// (kBytes / 16 rows of 16 bytes), loadRows8(p, stride) (min(8, kBytes / 8)
// rows of 8 bytes), broadcast16(p) (16 bytes into every 128-bit lane), sum(x)
// (of all u64 groups) and sadPartial(a, b, n) (SAD of n < kBytes bytes); for the grid search
// (vector_grid_search.h) also kGridBatch (candidates per batch, a multiple of
// 4), ones(), unpackLow64(x, y) / unpackHigh64(x, y) (per 128-bit lane, the
// low / high 64 bits of x and y), bitOr(x, y), shiftLeft64By32(x),
// shiftLeft32By16(x) and minU32(x, y) (unsigned 32-bit minimum).
#pragma once

#include <algorithm>
#include <cstring>

#include "robot/vision/block_matching/disparity_kernel_loops.h"
#include "robot/vision/block_matching/vector_grid_search.h"

namespace lineloc::sad_paths {
namespace {

template <class V>
struct VectorKernels {
  static constexpr int kRowsPerRegister = V::kBytes / 16;

  static uint32_t sad16x16(const uint8_t* a, ptrdiff_t a_stride, const uint8_t* b,
                           ptrdiff_t b_stride) {
    auto acc = V::zero();
    for (int r = 0; r < 16; r += kRowsPerRegister) {
      acc = V::add64(acc, V::sad(V::loadRows16(a + r * a_stride, a_stride),
                                 V::loadRows16(b + r * b_stride, b_stride)));
    }
    return V::sum(acc);
  }

  static uint32_t sad8x8(const uint8_t* a, ptrdiff_t a_stride, const uint8_t* b,
                         ptrdiff_t b_stride) {
    constexpr int kRows = std::min(8, V::kBytes / 8);
    auto acc = V::zero();
    for (int r = 0; r < 8; r += kRows) {
      acc = V::add64(acc, V::sad(V::loadRows8(a + r * a_stride, a_stride),
                                 V::loadRows8(b + r * b_stride, b_stride)));
    }
    return V::sum(acc);
  }

  static uint32_t sad(const uint8_t* a, ptrdiff_t a_stride, const uint8_t* b, ptrdiff_t b_stride,
                      int width, int height) {
    const int full = width - width % V::kBytes;
    auto acc = V::zero();
    uint32_t partial = 0;
    for (int r = 0; r < height; ++r, a += a_stride, b += b_stride) {
      for (int c = 0; c < full; c += V::kBytes) {
        acc = V::add64(acc, V::sad(V::load(a + c), V::load(b + c)));
      }
      if (full < width) {
        partial += V::sadPartial(a + full, b + full, width - full);
      }
    }
    return V::sum(acc) + partial;
  }

  static uint64_t psadbwProbe(int64_t loops) {
    alignas(64) uint8_t seed_bytes[V::kBytes] = {3, 1, 4, 1, 5, 9, 2, 6};
    const auto seed = V::load(seed_bytes);
    typename V::Reg chains[kPsadbwProbeChains];
    std::fill_n(chains, kPsadbwProbeChains, seed);
    for (int64_t i = 0; i < loops; ++i) {
#pragma GCC unroll 16
      for (int c = 0; c < kPsadbwProbeChains; ++c) {
        chains[c] = V::sad(chains[c], seed);
      }
    }
    auto total = V::zero();
    for (const auto& chain : chains) {
      total = V::add64(total, chain);
    }
    return V::sum(total);
  }

  static const SadKernels& table(SimdPath path) {
    static const SadKernels kernels{path,
                                    sad16x16,
                                    sad8x8,
                                    sad,
                                    VectorGridSearch<V>::run,
                                    DisparityLoops<uint16_t>::table(),
                                    DisparityLoops<uint32_t>::table(),
                                    psadbwProbe};
    return kernels;
  }
};

}  // namespace
}  // namespace lineloc::sad_paths
