// Sub-pixel position of a cost minimum from the costs c_-, c_0, c_+ at -1, 0,
// +1 around the integer minimum, by two models of the cost near its minimum:
//
//   parabola:    offset = (c_- - c_+) / (2 (c_- - 2 c_0 + c_+))
//   equiangular: offset = (c_- - c_+) / (2 (max(c_-, c_+) - c_0))
//
// both clamped to [-1/2, 1/2]. The equiangular fit (a V of equal slopes,
// Shimizu & Okutomi 2001, also cv::StereoBM's) is exact for the SAD of a
// locally linear signal, |d - t| * sum|gradient|, where the parabola is off by
// up to 0.086 px.
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

inline std::optional<float> equiangularOffset(uint32_t minus, uint32_t centre, uint32_t plus) {
  const double rise = static_cast<double>(std::max(minus, plus)) - centre;
  if (rise <= 0.0) {
    return std::nullopt;
  }
  return static_cast<float>(
      std::clamp((static_cast<double>(minus) - plus) / (2.0 * rise), -0.5, 0.5));
}

}  // namespace lineloc
