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
// |x - y|), absDiff(x, y) (per byte |x - y|), loadRows16(p, stride)
// (kBytes / 16 rows of 16 bytes), loadRows8(p, stride) (min(8, kBytes / 8)
// rows of 8 bytes), broadcast16(p) (16 bytes into every 128-bit lane), sum(x)
// (of all u64 groups), laneSums(x, out) (out[l] = sum of 128-bit lane l) and
// sadPartial(a, b, n) (SAD of n < kBytes bytes).
#pragma once

#include <algorithm>
#include <cstring>

#include "robot/vision/block_matching/sad_paths.h"

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

  // Candidates are packed into a strip of 16-byte rows, so that one register
  // load holds row r of kRowsPerRegister consecutive candidates; each 128-bit
  // lane then accumulates one candidate, and each load is reused by every
  // block row it meets (V_j serves (group g, block row r) with
  // kRowsPerRegister * g + r = j).
  static constexpr int kGroups = 4;
  static constexpr int kCandidatesPerPass = kGroups * kRowsPerRegister;
  static constexpr int kChunk = 64;
  static constexpr int kStripRows = kChunk + kCandidatesPerPass + 16;

  static void sadColumn16x16(const uint8_t* block, ptrdiff_t block_stride,
                             const uint8_t* candidates, ptrdiff_t stride, int count,
                             uint32_t* sads) {
    typename V::Reg reference[16];
    for (int r = 0; r < 16; ++r) {
      reference[r] = V::broadcast16(block + r * block_stride);
    }
    alignas(64) uint8_t strip[kStripRows * 16];
    for (int first = 0; first < count; first += kChunk) {
      const int chunk = std::min(kChunk, count - first);
      const int rows = chunk + 15;
      const uint8_t* source = candidates + first * stride;
      for (int r = 0; r < rows; ++r) {
        std::memcpy(strip + r * 16, source + r * stride, 16);
      }
      std::memset(strip + rows * 16, 0, (kStripRows - rows) * 16);
      sadStrip(reference, strip, chunk, sads + first);
    }
  }

  static void sadStrip(const typename V::Reg* reference, const uint8_t* strip, int count,
                       uint32_t* sads) {
    constexpr int kLoads = kRowsPerRegister * (kGroups - 1) + 16;
    for (int first = 0; first < count; first += kCandidatesPerPass) {
      typename V::Reg acc[kGroups];
      std::fill_n(acc, kGroups, V::zero());
      const uint8_t* rows = strip + first * 16;
#pragma GCC unroll 64
      for (int j = 0; j < kLoads; ++j) {
        const auto data = V::load(rows + j * 16);
#pragma GCC unroll 8
        for (int g = 0; g < kGroups; ++g) {
          const int r = j - kRowsPerRegister * g;
          if (r >= 0 && r < 16) {
            acc[g] = V::add64(acc[g], V::sad(data, reference[r]));
          }
        }
      }
      uint32_t pass[kCandidatesPerPass];
      for (int g = 0; g < kGroups; ++g) {
        V::laneSums(acc[g], pass + g * kRowsPerRegister);
      }
      std::copy_n(pass, std::min(kCandidatesPerPass, count - first), sads + first);
    }
  }

  static void absDiffRow(const uint8_t* a, const uint8_t* b, int width, uint8_t* out) {
    int i = 0;
    for (; i + V::kBytes <= width; i += V::kBytes) {
      V::store(out + i, V::absDiff(V::load(a + i), V::load(b + i)));
    }
    for (; i < width; ++i) {
      out[i] = static_cast<uint8_t>(a[i] > b[i] ? a[i] - b[i] : b[i] - a[i]);
    }
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
    static const SadKernels kernels{path,           sad16x16,   sad8x8,     sad,
                                    sadColumn16x16, absDiffRow, psadbwProbe};
    return kernels;
  }
};

// SAD of n bytes, one at a time: the tails of the narrower paths.
inline uint32_t sadBytes(const uint8_t* a, const uint8_t* b, int n) {
  uint32_t sum = 0;
  for (int i = 0; i < n; ++i) {
    sum += static_cast<uint32_t>(a[i] > b[i] ? a[i] - b[i] : b[i] - a[i]);
  }
  return sum;
}

}  // namespace
}  // namespace lineloc::sad_paths
