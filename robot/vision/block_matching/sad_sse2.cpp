// SSE2 path of the SAD kernels: `psadbw` on 16-byte registers.
#include <emmintrin.h>

#include "robot/vision/block_matching/sad_vector_kernels.h"

namespace lineloc::sad_paths {
namespace {

struct Sse2 {
  static constexpr int kBytes = 16;
  static constexpr int kGridBatch = 4;
  using Reg = __m128i;

  static Reg zero() { return _mm_setzero_si128(); }
  static Reg ones() { return _mm_set1_epi32(-1); }
  static Reg load(const uint8_t* p) { return _mm_loadu_si128(reinterpret_cast<const Reg*>(p)); }
  static void store(uint8_t* p, Reg x) { _mm_storeu_si128(reinterpret_cast<Reg*>(p), x); }
  static Reg load8(const uint8_t* p) { return _mm_loadl_epi64(reinterpret_cast<const Reg*>(p)); }
  static Reg add64(Reg x, Reg y) { return _mm_add_epi64(x, y); }
  static Reg sad(Reg x, Reg y) { return _mm_sad_epu8(x, y); }
  static Reg unpackLow64(Reg x, Reg y) { return _mm_unpacklo_epi64(x, y); }
  static Reg unpackHigh64(Reg x, Reg y) { return _mm_unpackhi_epi64(x, y); }
  static Reg bitOr(Reg x, Reg y) { return _mm_or_si128(x, y); }
  static Reg shiftLeft64By32(Reg x) { return _mm_slli_epi64(x, 32); }
  static Reg shiftLeft32By16(Reg x) { return _mm_slli_epi32(x, 16); }
  // SSE2 compares signed 32-bit lanes only: flip the sign bits first.
  static Reg minU32(Reg x, Reg y) {
    const Reg sign = _mm_set1_epi32(INT32_MIN);
    const Reg x_greater = _mm_cmpgt_epi32(_mm_xor_si128(x, sign), _mm_xor_si128(y, sign));
    return _mm_or_si128(_mm_and_si128(x_greater, y), _mm_andnot_si128(x_greater, x));
  }
  static Reg loadRows16(const uint8_t* p, ptrdiff_t) { return load(p); }
  static Reg loadRows8(const uint8_t* p, ptrdiff_t stride) {
    return _mm_unpacklo_epi64(load8(p), load8(p + stride));
  }
  static Reg broadcast16(const uint8_t* p) { return load(p); }
  static uint32_t sum(Reg x) {
    return static_cast<uint32_t>(_mm_cvtsi128_si32(x) + _mm_cvtsi128_si32(_mm_srli_si128(x, 8)));
  }
  static uint32_t sadPartial(const uint8_t* a, const uint8_t* b, int n) {
    if (n < 8) {
      return sadBytes(a, b, n);
    }
    return sum(sad(load8(a), load8(b))) + sadBytes(a + 8, b + 8, n - 8);
  }
};

}  // namespace

const SadKernels& sse2Kernels() {
  return VectorKernels<Sse2>::table(SimdPath::kSse2);
}

}  // namespace lineloc::sad_paths
