// Learnt lines of a repeating pattern (brick courses, tiles, railings, slats)
// are no landmarks: a matcher cannot tell one from its neighbour. A learnt
// line is dropped when another on the same building and plane, with the same
// side bright, runs along it (runsAlong: within max_angle_rad, both ends
// within min_separation_m across it, overlapping): the width of a tracking
// gate. Lines that alternate in brightness a few centimetres apart (a window
// frame's outer and inner edges) stay apart by their bright sides.
#pragma once

#include <cmath>
#include <vector>

#include "backbone/enrichment/surface_line_tracks.h"

namespace lineloc {

struct RepeatedLineOptions {
  double max_angle_rad = 3.0 * M_PI / 180.0;
  double min_separation_m = 0.25;
};

// The candidates that no other candidate repeats, in their order.
std::vector<LineCandidate> withoutRepeatedLines(const std::vector<LineCandidate>& candidates,
                                                const RepeatedLineOptions& options = {});

}  // namespace lineloc
