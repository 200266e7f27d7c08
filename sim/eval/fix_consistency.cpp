#include "sim/eval/fix_consistency.h"

#include <fmt/format.h>

#include <cmath>

#include "common/time/clock.h"
#include "common/time/percentile.h"
#include "sim/eval/trajectory_evaluation.h"

namespace lineloc {
namespace {

// NEES of `estimate` against the ground truth at `stamp_ns`; nullopt without it.
std::optional<double> neesAgainstTruth(const std::vector<StampedPose>& ground_truth,
                                       int64_t stamp_ns, const PoseWithCovariance& estimate,
                                       const FixConsistencyOptions& options) {
  const auto max_gap_ns = static_cast<int64_t>(options.max_ground_truth_gap_s * 1e9);
  const auto truth = interpolateGroundTruth(ground_truth, stamp_ns, max_gap_ns);
  if (!truth) {
    return std::nullopt;
  }
  return normalizedErrorSquared(estimate, *truth);
}

// "NEES median x, p99 y; K beyond chi2_6(0.9973) = b" over non-empty `nees`.
std::string formatNees(const std::vector<double>& nees, int beyond_bound,
                       const FixConsistencyOptions& options) {
  return fmt::format("NEES median {:.1f}, p99 {:.1f}; {} beyond chi2_6(0.9973) = {:.2f}",
                     percentile(nees, 50), percentile(nees, 99), beyond_bound, options.nees_bound);
}

}  // namespace

FixConsistency evaluateFixConsistency(const std::vector<StampedPose>& ground_truth,
                                      const std::vector<LoggedFix>& fixes,
                                      const FixConsistencyOptions& options) {
  FixConsistency consistency;
  consistency.answers = static_cast<int>(fixes.size());
  std::optional<int64_t> first_ok_stamp_ns;
  for (const LoggedFix& fix : fixes) {
    if (!first_ok_stamp_ns && fix.status == "ok") {
      first_ok_stamp_ns = fix.stamp_ns;
      consistency.first_ok_received_ns = fix.stamp_ns + fromMilliseconds(fix.latency_ms);
    }
    consistency.answers_from_first_ok +=
        first_ok_stamp_ns && fix.stamp_ns >= *first_ok_stamp_ns ? 1 : 0;
    if (fix.status != "ok") {
      continue;
    }
    ++consistency.ok;
    const std::optional<double> nees =
        neesAgainstTruth(ground_truth, fix.stamp_ns, fix.T_world_camera, options);
    if (!nees) {
      continue;
    }
    consistency.nees.push_back(*nees);
    consistency.beyond_bound += *nees > options.nees_bound ? 1 : 0;
  }
  return consistency;
}

namespace {

// "N answers, M ok", and when there was an OK fix, "(x % of the K answers from the first on)".
std::string formatAnswers(const FixConsistency& consistency) {
  std::string answers = fmt::format("{} answers, {} ok", consistency.answers, consistency.ok);
  if (consistency.answers_from_first_ok > 0) {
    answers +=
        fmt::format(" ({:.1f} % of the {} from the first on)",
                    100.0 * consistency.ok / static_cast<double>(consistency.answers_from_first_ok),
                    consistency.answers_from_first_ok);
  }
  return answers;
}

}  // namespace

std::string formatFixConsistency(const FixConsistency& consistency,
                                 const FixConsistencyOptions& options) {
  if (consistency.nees.empty()) {
    return fmt::format("fixes: {}, none with ground truth\n", formatAnswers(consistency));
  }
  return fmt::format(
      "fixes: {}; {} (precise wrong poses, {:.2f} % of {} with ground truth)\n",
      formatAnswers(consistency), formatNees(consistency.nees, consistency.beyond_bound, options),
      100.0 * consistency.beyond_bound / static_cast<double>(consistency.nees.size()),
      consistency.nees.size());
}

StateConsistency evaluateStateConsistency(const std::vector<StampedPose>& ground_truth,
                                          const std::vector<StampedPoseWithCovariance>& states,
                                          int64_t from_ns, const FixConsistencyOptions& options) {
  StateConsistency consistency;
  for (const StampedPoseWithCovariance& state : states) {
    if (state.stamp_ns < from_ns) {
      continue;
    }
    ++consistency.states;
    const std::optional<double> nees =
        neesAgainstTruth(ground_truth, state.stamp_ns, state.pose, options);
    if (!nees) {
      continue;
    }
    consistency.nees.push_back(*nees);
    consistency.beyond_bound += *nees > options.nees_bound ? 1 : 0;
  }
  return consistency;
}

std::string formatStateConsistency(const StateConsistency& consistency,
                                   const FixConsistencyOptions& options) {
  if (consistency.nees.empty()) {
    return fmt::format("robot states: {}, none with ground truth\n", consistency.states);
  }
  return fmt::format(
      "robot states: {} from the first OK fix on; {} (the robot sure of a wrong pose, {:.2f} % "
      "of {} with ground truth)\n",
      consistency.states, formatNees(consistency.nees, consistency.beyond_bound, options),
      100.0 * consistency.beyond_bound / static_cast<double>(consistency.nees.size()),
      consistency.nees.size());
}

}  // namespace lineloc
