// What lineloc-eval does: an estimated TUM trajectory against ground truth in
// the map frame (trajectory_evaluation.h), the error table and the evaluation
// plot (evaluation_plot.h); with the robot's fix log, how consistent the
// backbone's fixes were (fix_consistency.h), when the first OK fix came after
// the robot first moved, and the accuracy from that fix on; with its state
// log, how consistent the robot's own reported states were.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "sim/eval/trajectory_evaluation.h"

namespace lineloc {

struct EvaluationReportConfig {
  std::string ground_truth;
  std::string estimate;
  // The robot's fix log and state log; empty: none.
  std::string fix_log;
  std::string state_log;
  // PNG written; empty: none.
  std::string plot = "evaluation.png";
  // City model whose footprints the plot shows; empty: none.
  std::string city_model;
  // Model coordinates x y z of the trajectories' origin; empty: the model's default.
  std::vector<double> site_origin;
  double rpe_delta_s = 1.0;
  double position_threshold_m = 0.05;
  double rotation_threshold_deg = 0.5;
  double max_ground_truth_gap_s = 0.5;
  // The robot first moves when its ground truth first lies this far from its start.
  double motion_distance_m = 0.05;
  // Lines learnt from the drive (lineloc-enrich --out) scored against the
  // dataset's façade edges (facade_edges.txt); empty: none.
  std::string learnt_lines;
  std::string facade_edges;
  // ... and the lines on the street's clutter counted (clutter.txt); empty: not.
  std::string clutter;
};

// Writes the report to `out` and the plot; returns the whole trajectory's
// evaluation status. Throws std::runtime_error naming the file or option that
// is missing or malformed.
EvaluationStatus runEvaluationReport(const EvaluationReportConfig& config, std::ostream& out);

}  // namespace lineloc
