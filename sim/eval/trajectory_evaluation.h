// Accuracy of an estimated trajectory against ground truth, in the map frame
// and without any alignment (lineloc localises in absolute coordinates, so an
// offset is an error, not a gauge freedom). Ground truth is interpolated at
// each estimate's stamp (linear position, slerped rotation). Reports the
// absolute errors (Sturm et al., "A benchmark for the evaluation of RGB-D SLAM
// systems", IROS 2012, ATE without alignment), the relative pose error over a
// fixed time step (RPE, same paper eq. 1-2), the fraction of frames within the
// centimetre target, and how long the system took to fix its pose.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "common/trajectory/tum_trajectory.h"

namespace lineloc {

struct EvaluationOptions {
  // Time step of the relative pose error (s).
  double rpe_delta_s = 1.0;
  // A frame is "within" when both errors are at most these.
  double position_threshold_m = 0.05;
  double rotation_threshold_rad = 0.5 * 3.14159265358979323846 / 180.0;
  // Ground truth is not interpolated across gaps longer than this (s).
  double max_ground_truth_gap_s = 0.5;
  // Estimates stamped earlier are left out (the error "after the first fix").
  int64_t evaluate_from_ns = std::numeric_limits<int64_t>::min();
};

struct ErrorStatistics {
  double rmse = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double max = 0.0;
};

// One estimate compared with the interpolated ground truth.
struct FrameError {
  int64_t stamp_ns = 0;
  Eigen::Vector3d position_error_m = Eigen::Vector3d::Zero();  // estimate - truth, map frame
  double rotation_error_rad = 0.0;                             // angle of R_truth^T R_estimate
};

enum class EvaluationStatus { kOk, kNoGroundTruth, kNoOverlap };

struct TrajectoryEvaluation {
  EvaluationStatus status = EvaluationStatus::kNoOverlap;
  int estimates = 0;
  // Estimates with ground truth at their stamp.
  int matched = 0;
  std::vector<FrameError> frames;
  ErrorStatistics position_m;
  ErrorStatistics rotation_rad;
  // Per-axis RMSE of the position error (x east, y north, z up).
  Eigen::Vector3d axis_rmse_m = Eigen::Vector3d::Zero();
  ErrorStatistics rpe_translation_m;
  ErrorStatistics rpe_rotation_rad;
  int rpe_pairs = 0;
  double fraction_within = 0.0;
  // From the first ground-truth stamp to the first estimate, and to the first
  // estimate within the thresholds; empty when there is none.
  std::optional<double> time_to_first_fix_s;
  std::optional<double> time_to_first_good_fix_s;
};

// Ground truth (sorted by time) at `stamp_ns`: linear in position, slerped in
// rotation; nothing outside its span or across a gap longer than max_gap_ns.
std::optional<Eigen::Isometry3d> interpolateGroundTruth(const std::vector<StampedPose>& truth,
                                                        int64_t stamp_ns, int64_t max_gap_ns);

// The first ground-truth stamp (sorted by time) at which the camera lies more
// than `distance_m` from where it starts: when the robot first moves;
// nullopt when it never does.
std::optional<int64_t> firstMotionStamp_ns(const std::vector<StampedPose>& ground_truth,
                                           double distance_m);

// Both trajectories sorted by time. kNoGroundTruth: fewer than two ground-truth
// poses. kNoOverlap: no estimate falls inside the ground truth's time span.
TrajectoryEvaluation evaluateTrajectory(const std::vector<StampedPose>& ground_truth,
                                        const std::vector<StampedPose>& estimate,
                                        const EvaluationOptions& options);

// The report as a plain-text table (metres and degrees).
std::string formatEvaluationTable(const TrajectoryEvaluation& evaluation,
                                  const EvaluationOptions& options);

}  // namespace lineloc
