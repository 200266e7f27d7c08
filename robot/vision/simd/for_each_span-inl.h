// Runs a SIMD row kernel over a column range: whole vectors of the target's
// width, then the remainder in vectors of half, quarter, ... the width down
// to one lane, through the same code, so every kernel has exactly one body
// for all instruction sets and no out-of-range access, and a remainder costs
// at most log2(lanes) steps.
//
// Include after <hwy/highway.h> (re-included per target by
// hwy/foreach_target.h).

// Per-target include guard (Highway's convention for -inl.h headers).
#if defined(LINELOC_ROBOT_VISION_SIMD_FOR_EACH_SPAN_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef LINELOC_ROBOT_VISION_SIMD_FOR_EACH_SPAN_INL_H_
#undef LINELOC_ROBOT_VISION_SIMD_FOR_EACH_SPAN_INL_H_
#else
#define LINELOC_ROBOT_VISION_SIMD_FOR_EACH_SPAN_INL_H_
#endif

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace lineloc {
namespace HWY_NAMESPACE {

// Calls span(tag, x) for x in [begin, end): tag `d` while a whole vector
// fits, then tags of half as many lanes.
template <class D, class Span>
void forEachSpan(D d, int begin, int end, Span span) {
  const int lanes = static_cast<int>(hwy::HWY_NAMESPACE::Lanes(d));
  int x = begin;
  for (; x + lanes <= end; x += lanes) {
    span(d, x);
  }
  if constexpr (hwy::HWY_NAMESPACE::MaxLanes(D()) > 1) {
    forEachSpan(hwy::HWY_NAMESPACE::Half<D>(), x, end, span);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace lineloc
HWY_AFTER_NAMESPACE();

#endif  // LINELOC_ROBOT_VISION_SIMD_FOR_EACH_SPAN_INL_H_
