// Room a buffer filled by appendSelected (append_selected-inl.h) needs past
// its last element: one whole vector of 32-bit lanes of the widest vector
// Highway targets (2048-bit SVE).
#pragma once

namespace lineloc {

inline constexpr int kCompressSlack = 64;

}  // namespace lineloc
