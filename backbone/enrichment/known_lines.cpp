#include "backbone/enrichment/known_lines.h"

#include <algorithm>

#include "common/geometry/line_segments.h"

namespace lineloc {

std::vector<LineCandidate> withoutModelLines(const std::vector<LineCandidate>& candidates,
                                             const std::vector<ModelSegment>& model_lines,
                                             const KnownLineOptions& options) {
  std::vector<LineCandidate> unknown;
  for (const LineCandidate& candidate : candidates) {
    if (std::none_of(model_lines.begin(), model_lines.end(), [&](const ModelSegment& model) {
          return runsAlong(model.start_world, model.end_world, candidate.line.start_world,
                           candidate.line.end_world, options.max_angle_rad, options.max_distance_m);
        })) {
      unknown.push_back(candidate);
    }
  }
  return unknown;
}

}  // namespace lineloc
