#include "sim/eval/fix_consistency.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string_view>

#include "common/time/clock.h"
#include "common/time/percentile.h"
#include "sim/eval/trajectory_evaluation.h"

namespace lineloc {
namespace {

// Adds the NEES of `estimate` against the ground truth at `stamp_ns`, when
// there is ground truth there, to `tally`.
void addToTally(const std::vector<StampedPose>& ground_truth, int64_t stamp_ns,
                const PoseWithCovariance& estimate, const FixConsistencyOptions& options,
                NeesTally& tally) {
  const auto max_gap_ns = static_cast<int64_t>(options.max_ground_truth_gap_s * 1e9);
  const auto truth = interpolateGroundTruth(ground_truth, stamp_ns, max_gap_ns);
  if (!truth) {
    return;
  }
  const double nees = normalizedErrorSquared(estimate, *truth);
  tally.nees.push_back(nees);
  if (nees <= options.nees_bound) {
    return;
  }
  const Eigen::Vector3d error_m = estimate.pose.translation() - truth->translation();
  const Eigen::Vector3d direction = error_m.normalized();
  const double variance_along =
      direction.dot(estimate.covariance.topLeftCorner<3, 3>() * direction);
  tally.beyond_bound.push_back(
      {1e-9 * static_cast<double>(stamp_ns - ground_truth.front().stamp_ns), nees, error_m.norm(),
       std::sqrt(std::max(0.0, variance_along))});
}

// "NEES median x, p99 y; K beyond chi2_6(0.9973) = b (MEANING, z % of N with
// ground truth)\n" over a non-empty tally, then a line for each of the worst
// beyond the bound: "  beyond at t s: NEES n, e m off, sigma s m along it".
std::string formatTally(const NeesTally& tally, const FixConsistencyOptions& options,
                        std::string_view meaning) {
  const size_t beyond = tally.beyond_bound.size();
  std::string text = fmt::format(
      "NEES median {:.1f}, p99 {:.1f}; {} beyond chi2_6(0.9973) = {:.2f} ({}, {:.2f} % of {} "
      "with ground truth)\n",
      percentile(tally.nees, 50), percentile(tally.nees, 99), beyond, options.nees_bound, meaning,
      100.0 * static_cast<double>(beyond) / static_cast<double>(tally.nees.size()),
      tally.nees.size());
  std::vector<BeyondBound> worst = tally.beyond_bound;
  const auto listed = worst.begin() + std::min<ptrdiff_t>(kListedBeyondBound, worst.size());
  std::partial_sort(worst.begin(), listed, worst.end(),
                    [](const BeyondBound& a, const BeyondBound& b) { return a.nees > b.nees; });
  std::sort(worst.begin(), listed,
            [](const BeyondBound& a, const BeyondBound& b) { return a.time_s < b.time_s; });
  for (auto it = worst.begin(); it != listed; ++it) {
    text +=
        fmt::format("  beyond at {:.3f} s: NEES {:.1f}, {:.3f} m off, sigma {:.3f} m along it\n",
                    it->time_s, it->nees, it->position_error_m, it->sigma_along_error_m);
  }
  return text;
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
    addToTally(ground_truth, fix.stamp_ns, fix.T_world_camera, options, consistency.tally);
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
  if (consistency.tally.nees.empty()) {
    return fmt::format("fixes: {}, none with ground truth\n", formatAnswers(consistency));
  }
  return fmt::format("fixes: {}; {}", formatAnswers(consistency),
                     formatTally(consistency.tally, options, "precise wrong poses"));
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
    addToTally(ground_truth, state.stamp_ns, state.pose, options, consistency.tally);
  }
  return consistency;
}

std::string formatStateConsistency(const StateConsistency& consistency,
                                   const FixConsistencyOptions& options) {
  if (consistency.tally.nees.empty()) {
    return fmt::format("robot states: {}, none with ground truth\n", consistency.states);
  }
  return fmt::format("robot states: {} from the first OK fix on; {}", consistency.states,
                     formatTally(consistency.tally, options, "the robot sure of a wrong pose"));
}

}  // namespace lineloc
