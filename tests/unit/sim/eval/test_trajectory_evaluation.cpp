#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

#include "sim/eval/trajectory_evaluation.h"
#include "tests/unit/sim/eval/circle_drive.h"

namespace lineloc {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

std::vector<StampedPose> offsetBy(std::vector<StampedPose> poses, const Eigen::Vector3d& offset_m,
                                  double yaw_rad) {
  for (StampedPose& pose : poses) {
    pose.pose.translation() += offset_m;
    pose.pose.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                         pose.pose.linear();
  }
  return poses;
}

TEST(TrajectoryEvaluation, ConstantOffsetIsAnAbsoluteErrorButNoRelativeOne) {
  const auto truth = circleDrive(20.0, 30.0);
  const auto estimate = offsetBy(truth, {0.03, -0.04, 0.0}, 0.0);
  const TrajectoryEvaluation evaluation = evaluateTrajectory(truth, estimate, EvaluationOptions{});
  ASSERT_EQ(evaluation.status, EvaluationStatus::kOk);
  EXPECT_EQ(evaluation.matched, static_cast<int>(truth.size()));
  // Exact arithmetic gives 5 cm everywhere; the TUM-free double path only rounds.
  EXPECT_NEAR(evaluation.position_m.rmse, 0.05, 1e-12);
  EXPECT_NEAR(evaluation.position_m.median, 0.05, 1e-12);
  EXPECT_NEAR(evaluation.position_m.max, 0.05, 1e-12);
  EXPECT_NEAR(evaluation.axis_rmse_m.x(), 0.03, 1e-12);
  EXPECT_NEAR(evaluation.axis_rmse_m.y(), 0.04, 1e-12);
  EXPECT_NEAR(evaluation.axis_rmse_m.z(), 0.0, 1e-12);
  EXPECT_NEAR(evaluation.rotation_rad.max, 0.0, 1e-7);
  // A world-frame translation cancels in P_i^-1 P_j.
  EXPECT_NEAR(evaluation.rpe_translation_m.max, 0.0, 1e-9);
  EXPECT_GT(evaluation.rpe_pairs, 500);
  EXPECT_DOUBLE_EQ(evaluation.time_to_first_fix_s.value(), 0.0);
}

TEST(TrajectoryEvaluation, FractionWithinCountsBothThresholds) {
  const auto truth = circleDrive(20.0, 10.0);
  auto estimate = offsetBy(truth, {0.02, 0.0, 0.0}, 0.3 * kDegree);
  // The second half is 6 cm off: outside 5 cm.
  for (size_t i = estimate.size() / 2; i < estimate.size(); ++i) {
    estimate[i].pose.translation().x() += 0.04;
  }
  const TrajectoryEvaluation evaluation = evaluateTrajectory(truth, estimate, EvaluationOptions{});
  EXPECT_NEAR(evaluation.fraction_within, 100.0 / 201.0, 1e-12);
  EXPECT_NEAR(evaluation.rotation_rad.median, 0.3 * kDegree, 1e-9);
  const auto rotated = offsetBy(truth, Eigen::Vector3d::Zero(), 0.6 * kDegree);
  EXPECT_EQ(evaluateTrajectory(truth, rotated, EvaluationOptions{}).fraction_within, 0.0);
}

TEST(TrajectoryEvaluation, RelativeErrorMeasuresDriftPerStep) {
  const auto truth = circleDrive(20.0, 20.0);
  auto estimate = truth;
  // Drift of 1 cm/s east: over the 1 s RPE step the relative error is 1 cm.
  for (StampedPose& pose : estimate) {
    pose.pose.translation().x() +=
        0.01 * static_cast<double>(pose.stamp_ns - truth[0].stamp_ns) / 1e9;
  }
  const TrajectoryEvaluation evaluation = evaluateTrajectory(truth, estimate, EvaluationOptions{});
  EXPECT_NEAR(evaluation.rpe_translation_m.median, 0.01, 1e-9);
  EXPECT_NEAR(evaluation.rpe_translation_m.max, 0.01, 1e-9);
  EXPECT_NEAR(evaluation.position_m.max, 0.2, 1e-9);
}

TEST(TrajectoryEvaluation, InterpolatesGroundTruthAtEstimateStamps) {
  const auto truth = circleDrive(10.0, 10.0);
  // Estimates exactly on the circle, between ground-truth samples.
  auto estimate = circleDrive(7.0, 9.0, 1'000'000'000 + 25'000'000);
  const TrajectoryEvaluation evaluation = evaluateTrajectory(truth, estimate, EvaluationOptions{});
  ASSERT_EQ(evaluation.matched, static_cast<int>(estimate.size()));
  // Chord vs arc between samples 0.2 m apart on a 20 m circle: sagitta
  // s^2 / (8 r) = 0.04 / 160 = 0.25 mm at most.
  EXPECT_LT(evaluation.position_m.max, 3e-4);
  EXPECT_LT(evaluation.rotation_rad.max, 1e-9);
  EXPECT_NEAR(evaluation.time_to_first_fix_s.value(), 0.025, 1e-9);
}

TEST(TrajectoryEvaluation, TimeToFirstFixAndFirstGoodFix) {
  const auto truth = circleDrive(20.0, 10.0);
  std::vector<StampedPose> estimate(truth.begin() + 50, truth.end());  // from 2.5 s
  for (size_t i = 0; i < 20; ++i) {
    estimate[i].pose.translation().z() += 1.0;  // converging for 1 s
  }
  const TrajectoryEvaluation evaluation = evaluateTrajectory(truth, estimate, EvaluationOptions{});
  EXPECT_NEAR(evaluation.time_to_first_fix_s.value(), 2.5, 1e-9);
  EXPECT_NEAR(evaluation.time_to_first_good_fix_s.value(), 3.5, 1e-9);
  EXPECT_NE(formatEvaluationTable(evaluation, EvaluationOptions{}).find("2.500 s"),
            std::string::npos);
}

TEST(TrajectoryEvaluation, LeavesOutEstimatesBeforeTheStartOfEvaluation) {
  const auto truth = circleDrive(20.0, 10.0);
  auto estimate = truth;
  for (size_t i = 0; i < 40; ++i) {
    estimate[i].pose.translation().x() += 8.0;  // the DGPS start, before the first fix
  }
  EvaluationOptions options;
  options.evaluate_from_ns = estimate[40].stamp_ns;
  const TrajectoryEvaluation evaluation = evaluateTrajectory(truth, estimate, options);
  EXPECT_EQ(evaluation.matched, static_cast<int>(truth.size()) - 40);
  EXPECT_NEAR(evaluation.position_m.max, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(evaluation.fraction_within, 1.0);
  EXPECT_GT(evaluateTrajectory(truth, estimate, EvaluationOptions{}).position_m.rmse, 3.0);
}

TEST(TrajectoryEvaluation, ReportsMissingOverlapAndGroundTruth) {
  const auto truth = circleDrive(20.0, 5.0);
  const auto later = circleDrive(20.0, 5.0, 100'000'000'000);
  EXPECT_EQ(evaluateTrajectory(truth, later, EvaluationOptions{}).status,
            EvaluationStatus::kNoOverlap);
  EXPECT_EQ(evaluateTrajectory({truth[0]}, truth, EvaluationOptions{}).status,
            EvaluationStatus::kNoGroundTruth);
  // Gaps in the ground truth longer than the limit are not bridged.
  std::vector<StampedPose> gappy = {truth.front(), truth.back()};
  EXPECT_EQ(evaluateTrajectory(gappy, {truth[40]}, EvaluationOptions{}).status,
            EvaluationStatus::kNoOverlap);
  EXPECT_NE(formatEvaluationTable(evaluateTrajectory(truth, later, EvaluationOptions{}),
                                  EvaluationOptions{})
                .find("no evaluation"),
            std::string::npos);
}

TEST(FirstMotionStamp, IsWhenTheCameraFirstLiesFartherThanTheDistanceFromItsStart) {
  std::vector<StampedPose> truth(50);
  for (size_t i = 0; i < truth.size(); ++i) {
    truth[i].stamp_ns = static_cast<int64_t>(i) * 100'000'000;
    // Standing for 2 s, then driving east at 1 m/s.
    truth[i].pose.translation().x() = std::max(0.0, 0.1 * static_cast<double>(i) - 2.0);
  }
  EXPECT_EQ(firstMotionStamp_ns(truth, 0.05), std::optional<int64_t>(2'100'000'000));
  EXPECT_EQ(firstMotionStamp_ns(truth, 0.25), std::optional<int64_t>(2'300'000'000));
  EXPECT_EQ(firstMotionStamp_ns(truth, 10.0), std::nullopt);
  EXPECT_EQ(firstMotionStamp_ns({}, 0.05), std::nullopt);
}

}  // namespace
}  // namespace lineloc
