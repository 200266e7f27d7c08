// Learnt lines the map already holds. A candidate is a model line seen again
// (a crease the matcher did not use in the frames it came from, or a surveyed
// line a little off) when it runs within max_angle_rad of the model line,
// both its ends lie within max_distance_m of that line, and the two overlap
// along it. The default distance is three times the survey error the matcher
// assumes of model lines (3 cm).
#pragma once

#include <cmath>
#include <vector>

#include "backbone/enrichment/surface_line_tracks.h"
#include "backbone/visibility/visible_lines.h"

namespace lineloc {

struct KnownLineOptions {
  double max_angle_rad = 3.0 * M_PI / 180.0;
  double max_distance_m = 0.09;
};

// The candidates that are not model lines, in their order.
std::vector<LineCandidate> withoutModelLines(const std::vector<LineCandidate>& candidates,
                                             const std::vector<ModelSegment>& model_lines,
                                             const KnownLineOptions& options = {});

}  // namespace lineloc
