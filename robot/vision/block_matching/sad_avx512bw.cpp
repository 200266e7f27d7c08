// AVX-512BW path of the SAD kernels: `vpsadbw` on 64-byte registers, with
// masked loads for row tails.
#include <immintrin.h>

#include "robot/vision/block_matching/sad_vector_kernels.h"

namespace lineloc::sad_paths {
namespace {

struct Avx512Bw {
  static constexpr int kBytes = 64;
  static constexpr int kGridBatch = 12;
  using Reg = __m512i;

  static Reg zero() { return _mm512_setzero_si512(); }
  static Reg ones() { return _mm512_set1_epi32(-1); }
  static Reg load(const uint8_t* p) { return _mm512_loadu_si512(p); }
  static void store(uint8_t* p, Reg x) { _mm512_storeu_si512(p, x); }
  static __m128i load16(const uint8_t* p) {
    return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
  }
  static Reg add64(Reg x, Reg y) { return _mm512_add_epi64(x, y); }
  static Reg sad(Reg x, Reg y) { return _mm512_sad_epu8(x, y); }
  static Reg unpackLow64(Reg x, Reg y) { return _mm512_unpacklo_epi64(x, y); }
  static Reg unpackHigh64(Reg x, Reg y) { return _mm512_unpackhi_epi64(x, y); }
  static Reg bitOr(Reg x, Reg y) { return _mm512_or_si512(x, y); }
  static Reg shiftLeft64By32(Reg x) { return _mm512_slli_epi64(x, 32); }
  static Reg shiftLeft32By16(Reg x) { return _mm512_slli_epi32(x, 16); }
  static Reg minU32(Reg x, Reg y) { return _mm512_min_epu32(x, y); }
  static Reg loadRows16(const uint8_t* p, ptrdiff_t stride) {
    const __m256i low =
        _mm256_inserti128_si256(_mm256_castsi128_si256(load16(p)), load16(p + stride), 1);
    const __m256i high = _mm256_inserti128_si256(_mm256_castsi128_si256(load16(p + 2 * stride)),
                                                 load16(p + 3 * stride), 1);
    return _mm512_inserti64x4(_mm512_castsi256_si512(low), high, 1);
  }
  static Reg loadRows8(const uint8_t* p, ptrdiff_t stride) {
    const __m512i offsets = _mm512_setr_epi64(0, stride, 2 * stride, 3 * stride, 4 * stride,
                                              5 * stride, 6 * stride, 7 * stride);
    return _mm512_i64gather_epi64(offsets, p, 1);
  }
  static Reg broadcast16(const uint8_t* p) { return _mm512_broadcast_i32x4(load16(p)); }
  static uint32_t sum(Reg x) { return static_cast<uint32_t>(_mm512_reduce_add_epi64(x)); }
  static uint32_t sadPartial(const uint8_t* a, const uint8_t* b, int n) {
    const __mmask64 mask = (1ull << n) - 1;
    return sum(sad(_mm512_maskz_loadu_epi8(mask, a), _mm512_maskz_loadu_epi8(mask, b)));
  }
};

}  // namespace

const SadKernels& avx512BwKernels() {
  return VectorKernels<Avx512Bw>::table(SimdPath::kAvx512Bw);
}

}  // namespace lineloc::sad_paths
