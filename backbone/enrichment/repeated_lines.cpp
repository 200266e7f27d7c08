#include "backbone/enrichment/repeated_lines.h"

#include <algorithm>

#include "common/geometry/line_segments.h"

namespace lineloc {
namespace {

// Whether b repeats a (see the header).
bool repeats(const LineCandidate& a, const LineCandidate& b, const RepeatedLineOptions& options) {
  return a.building_id == b.building_id &&
         a.plane.normal.dot(b.plane.normal) >= std::cos(options.max_angle_rad) &&
         a.brighter_side.dot(b.brighter_side) > 0.0 &&
         runsAlong(a.line.start_world, a.line.end_world, b.line.start_world, b.line.end_world,
                   options.max_angle_rad, options.min_separation_m);
}

}  // namespace

std::vector<LineCandidate> withoutRepeatedLines(const std::vector<LineCandidate>& candidates,
                                                const RepeatedLineOptions& options) {
  std::vector<LineCandidate> distinct;
  for (size_t i = 0; i < candidates.size(); ++i) {
    bool repeated = false;
    for (size_t j = 0; j < candidates.size() && !repeated; ++j) {
      repeated = j != i && repeats(candidates[i], candidates[j], options);
    }
    if (!repeated) {
      distinct.push_back(candidates[i]);
    }
  }
  return distinct;
}

}  // namespace lineloc
