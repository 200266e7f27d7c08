#include "sim/render/lens_cover.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lineloc {

LensCover::LensCover(double start_s, double duration_s)
    : start_s_(start_s), duration_s_(duration_s) {
  if (!std::isfinite(start_s) || !std::isfinite(duration_s) || duration_s < 0.0) {
    throw std::invalid_argument(fmt::format(
        "lens cover: the start must be finite and the duration >= 0 s (got {} s for {} s)", start_s,
        duration_s));
  }
}

double LensCover::openFraction(double open_s, double close_s) const {
  if (close_s < open_s) {
    throw std::invalid_argument(fmt::format(
        "lens cover: an exposure must close after it opens (got {} s to {} s)", open_s, close_s));
  }
  const double end_s = start_s_ + duration_s_;
  if (close_s == open_s) {
    return open_s >= start_s_ && open_s < end_s ? 0.0 : 1.0;
  }
  const double covered_s = std::max(0.0, std::min(close_s, end_s) - std::max(open_s, start_s_));
  return 1.0 - covered_s / (close_s - open_s);
}

}  // namespace lineloc
