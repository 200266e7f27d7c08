#include "sim/eval/evaluation_report.h"

#include <fmt/format.h>

#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <ostream>

#include "sim/eval/enrichment_score.h"
#include "sim/eval/evaluation_plot.h"
#include "sim/eval/fix_consistency.h"
#include "sim/world/city_mesh.h"

namespace lineloc {
namespace {

// Footprints for the plot, in the same frame as the trajectories.
std::optional<SceneMesh> loadFootprints(const EvaluationReportConfig& config) {
  if (config.city_model.empty()) {
    return std::nullopt;
  }
  const citymodel::CityModel model = readCityModelFile(config.city_model);
  const Eigen::Vector3d origin = siteOriginOf(model, config.site_origin);
  return buildCityMesh(model, origin).mesh;
}

// How consistent the backbone's fixes and the robot's reported states were,
// and the trajectory's error from the first OK fix on (the accuracy bounds
// hold "after the first fix").
void printFixReport(const EvaluationReportConfig& config,
                    const std::vector<StampedPose>& ground_truth,
                    const std::vector<StampedPose>& estimate, EvaluationOptions evaluation_options,
                    std::ostream& out) {
  const FixConsistencyOptions consistency_options{config.max_ground_truth_gap_s};
  const FixConsistency consistency =
      evaluateFixConsistency(ground_truth, readFixLog(config.fix_log), consistency_options);
  out << formatFixConsistency(consistency, consistency_options);
  if (!consistency.first_ok_received_ns || ground_truth.empty()) {
    return;
  }
  if (!config.state_log.empty()) {
    out << formatStateConsistency(
        evaluateStateConsistency(ground_truth, readPoseCovarianceLog(config.state_log),
                                 *consistency.first_ok_received_ns, consistency_options),
        consistency_options);
  }
  evaluation_options.evaluate_from_ns = *consistency.first_ok_received_ns;
  if (const std::optional<int64_t> moved_ns =
          firstMotionStamp_ns(ground_truth, config.motion_distance_m)) {
    out << fmt::format(
        "\nthe robot first moved {:.3f} s after the ground truth starts; its first OK fix was "
        "received {:.3f} s after that\n",
        1e-9 * static_cast<double>(*moved_ns - ground_truth.front().stamp_ns),
        1e-9 * static_cast<double>(*consistency.first_ok_received_ns - *moved_ns));
  }
  out << fmt::format(
      "\nafter the first OK fix (received {:.3f} s after the ground truth starts):\n",
      1e-9 *
          static_cast<double>(*consistency.first_ok_received_ns - ground_truth.front().stamp_ns));
  out << formatEvaluationTable(evaluateTrajectory(ground_truth, estimate, evaluation_options),
                               evaluation_options);
}

void printEnrichmentScore(const EvaluationReportConfig& config, std::ostream& out) {
  if (config.facade_edges.empty()) {
    throw std::runtime_error("--learnt-lines needs --facade-edges, the drive's facade_edges.txt");
  }
  const EnrichmentScoreOptions options;
  const std::vector<ClutterBox> clutter =
      config.clutter.empty() ? std::vector<ClutterBox>() : readClutterBoxes(config.clutter);
  const EnrichmentScore score = scoreEnrichment(
      readLearntLines(config.learnt_lines), readFacadeEdges(config.facade_edges), clutter, options);
  out << fmt::format(
      "learnt lines: {}; distance to the nearest façade edge median {:.3f} m, {:.1f} % within "
      "{:.2f} m{}\n",
      score.lines, score.median_distance_m, 100.0 * score.within_fraction, options.within_m,
      config.clutter.empty() ? std::string()
                             : fmt::format("; {} on the street's clutter", score.on_clutter));
}

}  // namespace

EvaluationStatus runEvaluationReport(const EvaluationReportConfig& config, std::ostream& out) {
  if (config.ground_truth.empty() || config.estimate.empty()) {
    throw std::runtime_error("both --ground-truth and --estimate are required");
  }
  const EvaluationOptions evaluation_options{
      config.rpe_delta_s, config.position_threshold_m,
      config.rotation_threshold_deg * std::numbers::pi / 180.0, config.max_ground_truth_gap_s};
  const auto ground_truth = readTumFile(config.ground_truth);
  const auto estimate = readTumFile(config.estimate);
  const TrajectoryEvaluation evaluation =
      evaluateTrajectory(ground_truth, estimate, evaluation_options);
  out << formatEvaluationTable(evaluation, evaluation_options);
  if (!config.fix_log.empty()) {
    printFixReport(config, ground_truth, estimate, evaluation_options, out);
  }
  if (!config.learnt_lines.empty()) {
    printEnrichmentScore(config, out);
  }
  const std::optional<SceneMesh> footprints = loadFootprints(config);
  const cv::Mat plot = drawEvaluationPlot(ground_truth, estimate, evaluation, evaluation_options,
                                          footprints ? &*footprints : nullptr);
  if (!config.plot.empty() && !cv::imwrite(config.plot, plot)) {
    throw std::runtime_error(fmt::format("cannot write plot '{}'", config.plot));
  }
  return evaluation.status;
}

}  // namespace lineloc
