// Sub-pixel position of a cost minimum from the costs c_-, c_0, c_+ at -1, 0,
// +1 around the integer minimum, by a parabola through the three:
//
//   offset = (c_- - c_+) / (2 (c_- - 2 c_0 + c_+)), clamped to [-1/2, 1/2].
//
// (The stereo matcher fits the equiangular V instead, exact for the SAD of a
// locally linear signal where the parabola is off by up to 0.086 px; see
// disparity_kernels.h.)
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>

namespace lineloc {

// nullopt when the cost does not rise on both sides (flat: no vertex).
inline std::optional<float> parabolaOffset(uint32_t minus, uint32_t centre, uint32_t plus) {
  const double curvature = static_cast<double>(minus) - 2.0 * centre + plus;
  if (curvature <= 0.0) {
    return std::nullopt;
  }
  return static_cast<float>(
      std::clamp((static_cast<double>(minus) - plus) / (2.0 * curvature), -0.5, 0.5));
}

}  // namespace lineloc
