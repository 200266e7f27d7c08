// AVX2 path of the SAD kernels: `vpsadbw` on 32-byte registers.
#include <immintrin.h>

#include "robot/vision/block_matching/sad_vector_kernels.h"

namespace lineloc::sad_paths {
namespace {

struct Avx2 {
  static constexpr int kBytes = 32;
  static constexpr int kGridBatch = 4;
  using Reg = __m256i;

  static Reg zero() { return _mm256_setzero_si256(); }
  static Reg ones() { return _mm256_set1_epi32(-1); }
  static Reg load(const uint8_t* p) { return _mm256_loadu_si256(reinterpret_cast<const Reg*>(p)); }
  static void store(uint8_t* p, Reg x) { _mm256_storeu_si256(reinterpret_cast<Reg*>(p), x); }
  static __m128i load16(const uint8_t* p) {
    return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
  }
  static __m128i load8(const uint8_t* p) {
    return _mm_loadl_epi64(reinterpret_cast<const __m128i*>(p));
  }
  static Reg add64(Reg x, Reg y) { return _mm256_add_epi64(x, y); }
  static Reg sad(Reg x, Reg y) { return _mm256_sad_epu8(x, y); }
  static Reg unpackLow64(Reg x, Reg y) { return _mm256_unpacklo_epi64(x, y); }
  static Reg unpackHigh64(Reg x, Reg y) { return _mm256_unpackhi_epi64(x, y); }
  static Reg bitOr(Reg x, Reg y) { return _mm256_or_si256(x, y); }
  static Reg shiftLeft64By32(Reg x) { return _mm256_slli_epi64(x, 32); }
  static Reg shiftLeft32By16(Reg x) { return _mm256_slli_epi32(x, 16); }
  static Reg minU32(Reg x, Reg y) { return _mm256_min_epu32(x, y); }
  static Reg loadRows16(const uint8_t* p, ptrdiff_t stride) {
    return _mm256_inserti128_si256(_mm256_castsi128_si256(load16(p)), load16(p + stride), 1);
  }
  static Reg loadRows8(const uint8_t* p, ptrdiff_t stride) {
    const __m128i low = _mm_unpacklo_epi64(load8(p), load8(p + stride));
    const __m128i high = _mm_unpacklo_epi64(load8(p + 2 * stride), load8(p + 3 * stride));
    return _mm256_inserti128_si256(_mm256_castsi128_si256(low), high, 1);
  }
  static Reg broadcast16(const uint8_t* p) { return _mm256_broadcastsi128_si256(load16(p)); }
  static uint32_t sum128(__m128i x) {
    return static_cast<uint32_t>(_mm_cvtsi128_si32(_mm_add_epi64(x, _mm_srli_si128(x, 8))));
  }
  static uint32_t sum(Reg x) {
    return sum128(_mm_add_epi64(_mm256_castsi256_si128(x), _mm256_extracti128_si256(x, 1)));
  }
  static uint32_t sadPartial(const uint8_t* a, const uint8_t* b, int n) {
    uint32_t total = 0;
    if (n >= 16) {
      total += sum128(_mm_sad_epu8(load16(a), load16(b)));
      a += 16, b += 16, n -= 16;
    }
    if (n >= 8) {
      total += sum128(_mm_sad_epu8(load8(a), load8(b)));
      a += 8, b += 8, n -= 8;
    }
    return total + sadBytes(a, b, n);
  }
};

}  // namespace

const SadKernels& avx2Kernels() {
  return VectorKernels<Avx2>::table(SimdPath::kAvx2);
}

}  // namespace lineloc::sad_paths
