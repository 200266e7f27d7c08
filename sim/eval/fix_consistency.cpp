#include "sim/eval/fix_consistency.h"

#include <fmt/format.h>

#include <cmath>

#include "common/time/clock.h"
#include "common/time/percentile.h"
#include "sim/eval/trajectory_evaluation.h"

namespace lineloc {

FixConsistency evaluateFixConsistency(const std::vector<StampedPose>& ground_truth,
                                      const std::vector<LoggedFix>& fixes,
                                      const FixConsistencyOptions& options) {
  const auto max_gap_ns = static_cast<int64_t>(options.max_ground_truth_gap_s * 1e9);
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
    const auto truth = interpolateGroundTruth(ground_truth, fix.stamp_ns, max_gap_ns);
    if (!truth) {
      continue;
    }
    const double nees = normalizedErrorSquared(fix.T_world_camera, *truth);
    consistency.nees.push_back(nees);
    consistency.beyond_bound += nees > options.nees_bound ? 1 : 0;
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
      "fixes: {}; NEES median {:.1f}, p99 {:.1f}; {} beyond chi2_6(0.9973) = "
      "{:.2f} (precise wrong poses, {:.2f} % of {} with ground truth)\n",
      formatAnswers(consistency), percentile(consistency.nees, 50),
      percentile(consistency.nees, 99), consistency.beyond_bound, options.nees_bound,
      100.0 * consistency.beyond_bound / static_cast<double>(consistency.nees.size()),
      consistency.nees.size());
}

}  // namespace lineloc
