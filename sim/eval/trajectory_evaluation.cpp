#include "sim/eval/trajectory_evaluation.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lineloc {
namespace {

constexpr double kNsPerSecond = 1e9;
constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;

double rotationAngle(const Eigen::Matrix3d& R) {
  return Eigen::AngleAxisd(Eigen::Quaterniond(R).normalized()).angle();
}

ErrorStatistics statistics(std::vector<double> values) {
  ErrorStatistics stats;
  if (values.empty()) {
    return stats;
  }
  double sum = 0.0;
  double sum_squares = 0.0;
  for (const double value : values) {
    sum += value;
    sum_squares += value * value;
    stats.max = std::max(stats.max, value);
  }
  const auto n = static_cast<double>(values.size());
  stats.mean = sum / n;
  stats.rmse = std::sqrt(sum_squares / n);
  const size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(middle),
                   values.end());
  stats.median = values[middle];
  if (values.size() % 2 == 0) {
    stats.median = 0.5 * (stats.median +
                          *std::max_element(values.begin(),
                                            values.begin() + static_cast<std::ptrdiff_t>(middle)));
  }
  return stats;
}

struct MatchedPose {
  int64_t stamp_ns;
  Eigen::Isometry3d truth;
  Eigen::Isometry3d estimate;
};

// RPE (Sturm et al. eq. 1): E_i = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j), with j the first
// frame at least delta after i.
void relativePoseErrors(const std::vector<MatchedPose>& matched, double delta_s,
                        TrajectoryEvaluation& evaluation) {
  const auto delta_ns = static_cast<int64_t>(std::llround(delta_s * kNsPerSecond));
  std::vector<double> translation;
  std::vector<double> rotation;
  size_t j = 0;
  for (size_t i = 0; i < matched.size(); ++i) {
    j = std::max(j, i + 1);
    while (j < matched.size() && matched[j].stamp_ns - matched[i].stamp_ns < delta_ns) {
      ++j;
    }
    if (j == matched.size()) {
      break;
    }
    const Eigen::Isometry3d truth_motion = matched[i].truth.inverse() * matched[j].truth;
    const Eigen::Isometry3d estimate_motion = matched[i].estimate.inverse() * matched[j].estimate;
    const Eigen::Isometry3d error = truth_motion.inverse() * estimate_motion;
    translation.push_back(error.translation().norm());
    rotation.push_back(rotationAngle(error.linear()));
  }
  evaluation.rpe_pairs = static_cast<int>(translation.size());
  evaluation.rpe_translation_m = statistics(translation);
  evaluation.rpe_rotation_rad = statistics(rotation);
}

}  // namespace

std::optional<int64_t> firstMotionStamp_ns(const std::vector<StampedPose>& ground_truth,
                                           double distance_m) {
  for (const StampedPose& pose : ground_truth) {
    if ((pose.pose.translation() - ground_truth.front().pose.translation()).norm() > distance_m) {
      return pose.stamp_ns;
    }
  }
  return std::nullopt;
}

std::optional<Eigen::Isometry3d> interpolateGroundTruth(const std::vector<StampedPose>& truth,
                                                        int64_t stamp_ns, int64_t max_gap_ns) {
  const auto after = std::lower_bound(
      truth.begin(), truth.end(), stamp_ns,
      [](const StampedPose& pose, int64_t stamp) { return pose.stamp_ns < stamp; });
  if (after == truth.end()) {
    return std::nullopt;
  }
  if (after->stamp_ns == stamp_ns) {
    return after->pose;
  }
  if (after == truth.begin() || after->stamp_ns - (after - 1)->stamp_ns > max_gap_ns) {
    return std::nullopt;
  }
  const StampedPose& before = *(after - 1);
  const double s = static_cast<double>(stamp_ns - before.stamp_ns) /
                   static_cast<double>(after->stamp_ns - before.stamp_ns);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(before.pose.linear())
                      .slerp(s, Eigen::Quaterniond(after->pose.linear()))
                      .toRotationMatrix();
  pose.translation() = (1.0 - s) * before.pose.translation() + s * after->pose.translation();
  return pose;
}

TrajectoryEvaluation evaluateTrajectory(const std::vector<StampedPose>& ground_truth,
                                        const std::vector<StampedPose>& estimate,
                                        const EvaluationOptions& options) {
  TrajectoryEvaluation evaluation;
  evaluation.estimates = static_cast<int>(estimate.size());
  if (ground_truth.size() < 2) {
    evaluation.status = EvaluationStatus::kNoGroundTruth;
    return evaluation;
  }
  const auto max_gap_ns = static_cast<int64_t>(options.max_ground_truth_gap_s * kNsPerSecond);
  const int64_t start_ns = ground_truth.front().stamp_ns;
  std::vector<MatchedPose> matched;
  std::vector<double> position_errors;
  std::vector<double> rotation_errors;
  Eigen::Vector3d axis_sum_squares = Eigen::Vector3d::Zero();
  int within = 0;
  for (const StampedPose& pose : estimate) {
    if (pose.stamp_ns < options.evaluate_from_ns) {
      continue;
    }
    const std::optional<Eigen::Isometry3d> truth =
        interpolateGroundTruth(ground_truth, pose.stamp_ns, max_gap_ns);
    if (!truth) {
      continue;
    }
    FrameError frame{pose.stamp_ns, pose.pose.translation() - truth->translation(),
                     rotationAngle(truth->linear().transpose() * pose.pose.linear())};
    const bool good = frame.position_error_m.norm() <= options.position_threshold_m &&
                      frame.rotation_error_rad <= options.rotation_threshold_rad;
    within += good;
    const double since_start_s = static_cast<double>(pose.stamp_ns - start_ns) / kNsPerSecond;
    if (!evaluation.time_to_first_fix_s) {
      evaluation.time_to_first_fix_s = since_start_s;
    }
    if (good && !evaluation.time_to_first_good_fix_s) {
      evaluation.time_to_first_good_fix_s = since_start_s;
    }
    position_errors.push_back(frame.position_error_m.norm());
    rotation_errors.push_back(frame.rotation_error_rad);
    axis_sum_squares += frame.position_error_m.cwiseAbs2();
    evaluation.frames.push_back(frame);
    matched.push_back({pose.stamp_ns, *truth, pose.pose});
  }
  evaluation.matched = static_cast<int>(matched.size());
  if (matched.empty()) {
    evaluation.status = EvaluationStatus::kNoOverlap;
    return evaluation;
  }
  evaluation.status = EvaluationStatus::kOk;
  evaluation.position_m = statistics(position_errors);
  evaluation.rotation_rad = statistics(rotation_errors);
  evaluation.axis_rmse_m = (axis_sum_squares / static_cast<double>(matched.size())).cwiseSqrt();
  evaluation.fraction_within = static_cast<double>(within) / static_cast<double>(matched.size());
  relativePoseErrors(matched, options.rpe_delta_s, evaluation);
  return evaluation;
}

std::string formatEvaluationTable(const TrajectoryEvaluation& evaluation,
                                  const EvaluationOptions& options) {
  if (evaluation.status == EvaluationStatus::kNoGroundTruth) {
    return "no evaluation: the ground truth has fewer than two poses\n";
  }
  if (evaluation.status == EvaluationStatus::kNoOverlap) {
    return fmt::format(
        "no evaluation: none of the {} estimates lies within the ground truth's "
        "time span\n",
        evaluation.estimates);
  }
  const auto row = [](const std::string& name, const ErrorStatistics& stats, double scale,
                      const std::string& unit) {
    return fmt::format("{:<24}{:>12.4f}{:>12.4f}{:>12.4f}{:>12.4f}  {}\n", name, stats.rmse * scale,
                       stats.mean * scale, stats.median * scale, stats.max * scale, unit);
  };
  const auto seconds = [](const std::optional<double>& value) {
    return value ? fmt::format("{:.3f} s", *value) : std::string("never");
  };
  std::string table =
      fmt::format("{:<24}{:>12}{:>12}{:>12}{:>12}\n", "error", "rmse", "mean", "median", "max");
  table += row("position", evaluation.position_m, 1.0, "m");
  table += row("attitude", evaluation.rotation_rad, kDegreesPerRadian, "deg");
  table += row(fmt::format("RPE translation / {:g} s", options.rpe_delta_s),
               evaluation.rpe_translation_m, 1.0, "m");
  table += row(fmt::format("RPE rotation / {:g} s", options.rpe_delta_s),
               evaluation.rpe_rotation_rad, kDegreesPerRadian, "deg");
  table += fmt::format("per-axis position rmse   x {:.4f}  y {:.4f}  z {:.4f} m\n",
                       evaluation.axis_rmse_m.x(), evaluation.axis_rmse_m.y(),
                       evaluation.axis_rmse_m.z());
  table += fmt::format(
      "within {:g} cm and {:g} deg   {:.1f} % of {} matched frames ({} estimates)\n",
      options.position_threshold_m * 100.0, options.rotation_threshold_rad * kDegreesPerRadian,
      100.0 * evaluation.fraction_within, evaluation.matched, evaluation.estimates);
  table += fmt::format("time to first fix        {}   to first fix within target {}\n",
                       seconds(evaluation.time_to_first_fix_s),
                       seconds(evaluation.time_to_first_good_fix_s));
  return table;
}

}  // namespace lineloc
