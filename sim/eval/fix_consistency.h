// The backbone's answers against ground truth (lineloc-eval --fix-log): each
// OK fix's normalized estimation error squared (NEES, common/geometry/pose.h)
// and the fixes beyond chi^2_6(0.9973), the 6-D equivalent of three sigma.
// Those are precise wrong poses, which the system must not give (paper §3.2):
// a consistent estimator exceeds the bound in 0.27 % of fixes. The robot's
// reported states (lineloc-eval --state-log) are checked alike: beyond the
// bound, the robot is sure of a wrong pose.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/trajectory/fix_log.h"
#include "common/trajectory/pose_covariance_log.h"
#include "common/trajectory/tum_trajectory.h"

namespace lineloc {

// How many of the estimates beyond the bound a report lists, the worst.
inline constexpr int kListedBeyondBound = 5;

struct FixConsistencyOptions {
  // Ground truth is not interpolated across gaps longer than this (s).
  double max_ground_truth_gap_s = 0.5;
  // chi^2_6(0.9973).
  double nees_bound = 20.06;
};

// An estimate beyond the bound: when, how far off its position was, and how
// sure of it along that error it was.
struct BeyondBound {
  // Its stamp, in seconds after the first ground-truth pose.
  double time_s = 0.0;
  double nees = 0.0;
  double position_error_m = 0.0;
  // sqrt(u^T Sigma_p u), u the position error's direction (0 when the
  // position is exact and the rotation is what is beyond).
  double sigma_along_error_m = 0.0;
};

// The NEES of estimates against ground truth, in log order (those without
// ground truth at their stamp left out), and the ones beyond the bound.
struct NeesTally {
  std::vector<double> nees;
  std::vector<BeyondBound> beyond_bound;
};

struct FixConsistency {
  int answers = 0;
  int ok = 0;
  // Answers to the frames from the first OK fix's on, that one included: the
  // share of them OK is the availability once the robot has been found.
  int answers_from_first_ok = 0;
  // When the robot received the first OK fix (its stamp plus its latency),
  // whether or not ground truth covers it: its estimate includes a fix from
  // the next frame stamped at or after this on.
  std::optional<int64_t> first_ok_received_ns;
  // Of the OK fixes.
  NeesTally tally;
};

FixConsistency evaluateFixConsistency(const std::vector<StampedPose>& ground_truth,
                                      const std::vector<LoggedFix>& fixes,
                                      const FixConsistencyOptions& options);

// One line: answers, OK fixes (and their share of the answers from the first
// OK fix on), NEES median and p99, fixes beyond the bound; then one line for
// each of the kListedBeyondBound worst of those.
std::string formatFixConsistency(const FixConsistency& consistency,
                                 const FixConsistencyOptions& options);

struct StateConsistency {
  int states = 0;
  NeesTally tally;
};

// The states stamped at or after `from_ns` (the first OK fix's arrival: before
// it the robot knows its pose from DGPS and compass alone).
StateConsistency evaluateStateConsistency(const std::vector<StampedPose>& ground_truth,
                                          const std::vector<StampedPoseWithCovariance>& states,
                                          int64_t from_ns, const FixConsistencyOptions& options);

// One line: states, NEES median and p99, states beyond the bound; then their
// worst, as for fixes.
std::string formatStateConsistency(const StateConsistency& consistency,
                                   const FixConsistencyOptions& options);

}  // namespace lineloc
