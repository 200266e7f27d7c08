// lineloc-eval: an estimated trajectory against ground truth, with the
// consistency of the robot's fixes and states (sim/eval/evaluation_report.h).
#include <spdlog/spdlog.h>

#include <iostream>

#include "common/config/program_options.h"
#include "sim/eval/evaluation_report.h"

int main(int argc, char** argv) {
  lineloc::EvaluationReportConfig config;
  lineloc::ProgramOptions options("lineloc-eval",
                                  "accuracy of an estimated trajectory against ground truth");
  options.add("ground_truth", config.ground_truth, "ground-truth TUM file (required)");
  options.add("estimate", config.estimate, "estimated TUM file (required)");
  options.add("fix_log", config.fix_log,
              "the robot's fix log (lineloc-robot --fix-log-out): each OK fix's error in its own "
              "covariance, and the fixes beyond 3 sigma (empty: none)");
  options.add("state_log", config.state_log,
              "the robot's state log (lineloc-robot --state-log-out), with --fix-log: each "
              "reported state's error in its own covariance from the first OK fix on, and the "
              "states beyond 3 sigma (empty: none)");
  options.add("plot", config.plot, "PNG written with the top view and errors over time");
  options.add("city_model", config.city_model,
              "city model whose footprints the plot shows (CityJSON / .jsonl; empty: none)");
  options.addFixedSize("site_origin", config.site_origin, 3,
                       "model coordinates of the trajectories' origin, x y z (empty: the model's "
                       "default, as lineloc-sim uses)");
  options.add("rpe_delta_s", config.rpe_delta_s, "time step of the relative pose error (s)");
  options.add("position_threshold_m", config.position_threshold_m,
              "a frame is within target when its position error is at most this (m)");
  options.add("rotation_threshold_deg", config.rotation_threshold_deg,
              "... and its attitude error at most this (deg)");
  options.add("max_ground_truth_gap_s", config.max_ground_truth_gap_s,
              "ground truth is not interpolated across longer gaps (s)");
  options.add("motion_distance_m", config.motion_distance_m,
              "the robot first moves when its ground truth first lies this far from its start (m)");
  options.add("learnt_lines", config.learnt_lines,
              "lines learnt from the drive (lineloc-enrich --out) to score against the façade "
              "edges (empty: none)");
  options.add("facade_edges", config.facade_edges,
              "with --learnt-lines: the simulated drive's facade_edges.txt");
  options.add("clutter", config.clutter,
              "with --learnt-lines: the simulated drive's clutter.txt, to count the learnt lines "
              "on parked cars, trees, poles and people (empty: not counted)");
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  try {
    return lineloc::runEvaluationReport(config, std::cout) == lineloc::EvaluationStatus::kOk ? 0
                                                                                             : 3;
  } catch (const std::exception& error) {
    spdlog::error("{}", error.what());
    return 1;
  }
}
