// Total order of block-matching candidates (Persa & Jonker §4 full search):
// the least SAD first; ties go to the shorter displacement (dx^2 + dy^2), then
// to the smaller dy, then dx, so that every search strategy and SIMD path
// picks the same winner.
#pragma once

#include <cstdint>
#include <vector>

namespace lineloc {

inline constexpr int kMaxSearchRadiusPx = 127;

// rank = SAD << 32 | (dx^2 + dy^2) << 16 | (dy + 127) << 8 | (dx + 127):
// a candidate precedes another iff its rank is smaller.
inline uint64_t candidateRank(uint32_t sad, int dx, int dy) {
  const uint64_t length2 = static_cast<uint64_t>(dx * dx + dy * dy);
  return (static_cast<uint64_t>(sad) << 32) | (length2 << 16) |
         (static_cast<uint64_t>(dy + kMaxSearchRadiusPx) << 8) |
         static_cast<uint64_t>(dx + kMaxSearchRadiusPx);
}

// Place of every displacement of the window |dx|, |dy| <= radius_px in the
// tie order (the low 32 bits of candidateRank), 0 first, at index
// (dy + radius_px) (2 radius_px + 1) + dx + radius_px. Fits 16 bits for
// radius_px <= kMaxSearchRadiusPx.
std::vector<uint16_t> tieOrder(int radius_px);

}  // namespace lineloc
