// Appends the selected lanes of a vector to an array: compress in a
// register, then store the whole vector. The memory form of compress is
// microcoded on some processors (AMD Zen 4, dozens of cycles), the register
// form is not; the price is kCompressSlack spare elements at the end of the
// array (compress_slack.h).
//
// Include after <hwy/highway.h> (re-included per target by
// hwy/foreach_target.h).

// Per-target include guard (Highway's convention for -inl.h headers).
#if defined(LINELOC_ROBOT_VISION_SIMD_APPEND_SELECTED_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef LINELOC_ROBOT_VISION_SIMD_APPEND_SELECTED_INL_H_
#undef LINELOC_ROBOT_VISION_SIMD_APPEND_SELECTED_INL_H_
#else
#define LINELOC_ROBOT_VISION_SIMD_APPEND_SELECTED_INL_H_
#endif

#include <hwy/highway.h>

#include "robot/vision/simd/compress_slack.h"

HWY_BEFORE_NAMESPACE();
namespace lineloc {
namespace HWY_NAMESPACE {

// Stores the lanes of `v` where `mask` is true at out[0], out[1], ... and
// returns their number; out[0 .. Lanes(d)) may be written.
template <class D, class V, class M>
size_t appendSelected(D d, V v, M mask, hwy::HWY_NAMESPACE::TFromD<D>* out) {
  static_assert(hwy::HWY_NAMESPACE::MaxLanes(D()) <= kCompressSlack);
  hwy::HWY_NAMESPACE::StoreU(hwy::HWY_NAMESPACE::Compress(v, mask), d, out);
  return hwy::HWY_NAMESPACE::CountTrue(d, mask);
}

}  // namespace HWY_NAMESPACE
}  // namespace lineloc
HWY_AFTER_NAMESPACE();

#endif  // LINELOC_ROBOT_VISION_SIMD_APPEND_SELECTED_INL_H_
