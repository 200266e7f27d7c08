// SSE2 path of the SAD kernels: `psadbw` on 16-byte registers.
#include <emmintrin.h>

#include "robot/vision/block_matching/sad_vector_kernels.h"

namespace lineloc::sad_paths {
namespace {

struct Sse2 {
  static constexpr int kBytes = 16;
  using Reg = __m128i;

  static Reg zero() { return _mm_setzero_si128(); }
  static Reg load(const uint8_t* p) { return _mm_loadu_si128(reinterpret_cast<const Reg*>(p)); }
  static void store(uint8_t* p, Reg x) { _mm_storeu_si128(reinterpret_cast<Reg*>(p), x); }
  static Reg load8(const uint8_t* p) { return _mm_loadl_epi64(reinterpret_cast<const Reg*>(p)); }
  static Reg add64(Reg x, Reg y) { return _mm_add_epi64(x, y); }
  static Reg sad(Reg x, Reg y) { return _mm_sad_epu8(x, y); }
  static Reg absDiff(Reg x, Reg y) {
    return _mm_or_si128(_mm_subs_epu8(x, y), _mm_subs_epu8(y, x));
  }
  static Reg loadRows16(const uint8_t* p, ptrdiff_t) { return load(p); }
  static Reg loadRows8(const uint8_t* p, ptrdiff_t stride) {
    return _mm_unpacklo_epi64(load8(p), load8(p + stride));
  }
  static Reg broadcast16(const uint8_t* p) { return load(p); }
  static uint32_t sum(Reg x) {
    return static_cast<uint32_t>(_mm_cvtsi128_si32(x) + _mm_cvtsi128_si32(_mm_srli_si128(x, 8)));
  }
  static void laneSums(Reg x, uint32_t* out) { out[0] = sum(x); }
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
