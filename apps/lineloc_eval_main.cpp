// lineloc-eval: compares an estimated TUM trajectory with ground truth in the
// map frame, prints the error table and writes the evaluation plot; with the
// robot's fix log, also how consistent the backbone's fixes were, and with its
// state log how consistent the robot's own reported states were.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <iostream>
#include <numbers>
#include <opencv2/imgcodecs.hpp>

#include "common/config/program_options.h"
#include "sim/eval/evaluation_plot.h"
#include "sim/eval/fix_consistency.h"
#include "sim/eval/trajectory_evaluation.h"
#include "sim/world/city_mesh.h"

namespace {

struct EvalConfig {
  std::string ground_truth;
  std::string estimate;
  std::string fix_log;
  std::string state_log;
  std::string plot = "evaluation.png";
  std::string city_model;
  std::vector<double> site_origin;
  double rpe_delta_s = 1.0;
  double position_threshold_m = 0.05;
  double rotation_threshold_deg = 0.5;
  double max_ground_truth_gap_s = 0.5;
  double motion_distance_m = 0.05;
};

// Footprints for the plot, in the same frame as the trajectories.
std::optional<lineloc::SceneMesh> loadFootprints(const EvalConfig& config) {
  if (config.city_model.empty()) {
    return std::nullopt;
  }
  const lineloc::citymodel::CityModel model = lineloc::readCityModelFile(config.city_model);
  if (!config.site_origin.empty() && config.site_origin.size() != 3) {
    throw std::runtime_error("site_origin must have three numbers x y z");
  }
  const Eigen::Vector3d origin =
      config.site_origin.empty()
          ? lineloc::defaultSiteOrigin(model)
          : Eigen::Vector3d(config.site_origin[0], config.site_origin[1], config.site_origin[2]);
  return lineloc::buildCityMesh(model, origin).mesh;
}

// How consistent the backbone's fixes and the robot's reported states were,
// and the trajectory's error from the first OK fix on (the accuracy bounds
// hold "after the first fix").
void printFixReport(const EvalConfig& config, const std::vector<lineloc::StampedPose>& ground_truth,
                    const std::vector<lineloc::StampedPose>& estimate,
                    lineloc::EvaluationOptions evaluation_options) {
  const lineloc::FixConsistencyOptions consistency_options{config.max_ground_truth_gap_s};
  const lineloc::FixConsistency consistency = lineloc::evaluateFixConsistency(
      ground_truth, lineloc::readFixLog(config.fix_log), consistency_options);
  std::cout << lineloc::formatFixConsistency(consistency, consistency_options);
  if (!consistency.first_ok_received_ns || ground_truth.empty()) {
    return;
  }
  if (!config.state_log.empty()) {
    std::cout << lineloc::formatStateConsistency(
        lineloc::evaluateStateConsistency(ground_truth,
                                          lineloc::readPoseCovarianceLog(config.state_log),
                                          *consistency.first_ok_received_ns, consistency_options),
        consistency_options);
  }
  evaluation_options.evaluate_from_ns = *consistency.first_ok_received_ns;
  if (const std::optional<int64_t> moved_ns =
          lineloc::firstMotionStamp_ns(ground_truth, config.motion_distance_m)) {
    std::cout << fmt::format(
        "\nthe robot first moved {:.3f} s after the ground truth starts; its first OK fix was "
        "received {:.3f} s after that\n",
        1e-9 * static_cast<double>(*moved_ns - ground_truth.front().stamp_ns),
        1e-9 * static_cast<double>(*consistency.first_ok_received_ns - *moved_ns));
  }
  std::cout << fmt::format(
      "\nafter the first OK fix (received {:.3f} s after the ground truth starts):\n",
      1e-9 *
          static_cast<double>(*consistency.first_ok_received_ns - ground_truth.front().stamp_ns));
  std::cout << lineloc::formatEvaluationTable(
      lineloc::evaluateTrajectory(ground_truth, estimate, evaluation_options), evaluation_options);
}

}  // namespace

int main(int argc, char** argv) {
  EvalConfig config;
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
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  try {
    if (config.ground_truth.empty() || config.estimate.empty()) {
      throw std::runtime_error("both --ground-truth and --estimate are required");
    }
    const lineloc::EvaluationOptions evaluation_options{
        config.rpe_delta_s, config.position_threshold_m,
        config.rotation_threshold_deg * std::numbers::pi / 180.0, config.max_ground_truth_gap_s};
    const auto ground_truth = lineloc::readTumFile(config.ground_truth);
    const auto estimate = lineloc::readTumFile(config.estimate);
    const lineloc::TrajectoryEvaluation evaluation =
        lineloc::evaluateTrajectory(ground_truth, estimate, evaluation_options);
    std::cout << lineloc::formatEvaluationTable(evaluation, evaluation_options);
    if (!config.fix_log.empty()) {
      printFixReport(config, ground_truth, estimate, evaluation_options);
    }
    const std::optional<lineloc::SceneMesh> footprints = loadFootprints(config);
    const cv::Mat plot =
        lineloc::drawEvaluationPlot(ground_truth, estimate, evaluation, evaluation_options,
                                    footprints ? &*footprints : nullptr);
    if (!config.plot.empty() && !cv::imwrite(config.plot, plot)) {
      throw std::runtime_error(fmt::format("cannot write plot '{}'", config.plot));
    }
    return evaluation.status == lineloc::EvaluationStatus::kOk ? 0 : 3;
  } catch (const std::exception& error) {
    spdlog::error("{}", error.what());
    return 1;
  }
}
