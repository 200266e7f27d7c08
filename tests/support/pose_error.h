// Thresholds for tests that check "no precise wrong pose" (paper §3.2): an
// estimate's normalized error (common/geometry/pose.h) against chi^2_6.
#pragma once

#include "common/geometry/pose.h"

namespace lineloc::test {

using lineloc::normalizedErrorSquared;
using lineloc::poseError;

// chi^2_6(0.9973): the 6-D equivalent of three standard deviations.
inline constexpr double kChi2Six9973 = 20.06;

// chi^2_6(0.999): a consistent estimate exceeds it once in a thousand trials.
inline constexpr double kChi2Six999 = 22.46;

}  // namespace lineloc::test
