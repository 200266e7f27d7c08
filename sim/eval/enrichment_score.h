// How well lines learnt from images (enrichment) match the façade detail the
// simulator painted (sim/world/facade_edges.h).
//
// A learnt line's distance is the mean, over points spread evenly along it
// (one per sample_spacing_m, at least five), of each point's distance to the
// nearest façade edge: a line along a row of signs is on their edges though
// each sign's edge is a piece of its own. The score gives the median and the
// fraction within within_m, and how many lines lie on the street's clutter
// (their points' mean distance to the nearest clutter box at most
// clutter_margin_m, and less than to the façade edges): lines a parked car, a
// tree, a pole or a person made.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "sim/world/clutter_boxes.h"
#include "sim/world/facade_edges.h"

namespace lineloc {

struct LearntLine {
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
};

struct EnrichmentScore {
  int lines = 0;
  double median_distance_m = 0.0;
  double within_fraction = 0.0;
  // Per line, in the order given (m; infinity when a point has no edge
  // within reach_m).
  std::vector<double> distances_m;
  int on_clutter = 0;
};

struct EnrichmentScoreOptions {
  double within_m = 0.10;
  double sample_spacing_m = 0.1;
  double clutter_margin_m = 0.1;
  // Edges farther than this from a point are not looked at.
  double reach_m = 1.0;
};

// Reads lineloc-enrich's output: the first six fields of each line that is
// not a '#' comment are x0 y0 z0 x1 y1 z1. Throws std::runtime_error naming
// the source (the file) and line of a malformed row.
std::vector<LearntLine> parseLearntLines(std::string_view text, const std::string& source);
std::vector<LearntLine> readLearntLines(const std::string& path);

EnrichmentScore scoreEnrichment(const std::vector<LearntLine>& lines,
                                const std::vector<FacadeEdge>& truth,
                                const std::vector<ClutterBox>& clutter = {},
                                const EnrichmentScoreOptions& options = {});

}  // namespace lineloc
