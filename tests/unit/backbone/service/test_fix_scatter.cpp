// A robot's recent answers as a floor under each new answer's covariance.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "backbone/service/fix_scatter.h"

namespace lineloc {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

constexpr int64_t kFrameNs = 33'333'333;
constexpr double kChi2SixDof9973 = 20.06;

// The answers' own covariance: 3 cm and 0.08 degrees.
const Matrix6d kAnswerCovariance = diagonalPoseCovariance(0.03, 0.08 * M_PI / 180.0);

// A robot driving at 1 m/s along a gentle bend, its camera looking along x.
Eigen::Isometry3d truePose(int frame) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.002 * frame, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(40.0 + frame / 30.0, -20.0 + 0.0005 * frame * frame, 1.6);
  return pose;
}

// Its odometry: the same motion in a frame of its own.
OdometryPose odometryAt(int frame) {
  Eigen::Isometry3d T_odom_world = Eigen::Isometry3d::Identity();
  T_odom_world.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_odom_world.translation() = Eigen::Vector3d(-35.0, 12.0, 0.0);
  return {T_odom_world * truePose(frame), 3};
}

PoseWithCovariance answerAt(int frame, const Vector6d& error) {
  return {applyPoseError(truePose(frame), error), kAnswerCovariance};
}

double positionSigmaRatio(const Matrix6d& raised, const Matrix6d& reported) {
  return std::sqrt(raised.topLeftCorner<3, 3>().trace() / reported.topLeftCorner<3, 3>().trace());
}

// The answers flip between the truth and a neighbouring alignment 0.25 degrees
// of yaw and 10 cm sideways from it, each reporting its own basin's
// covariance: the other basin lies beyond three sigma of it.
TEST(FixScatter, CoversTheOtherBasinOfAnswersThatFlipBetweenTwo) {
  Vector6d other_basin = Vector6d::Zero();
  other_basin(1) = 0.10;
  other_basin(5) = 0.25 * M_PI / 180.0;
  ASSERT_GT(other_basin.dot(kAnswerCovariance.ldlt().solve(other_basin)), kChi2SixDof9973);
  FixScatter scatter;
  int wrong_answers = 0;
  for (int frame = 0; frame < 60; ++frame) {
    const bool in_other_basin = frame % 3 != 0;
    const PoseWithCovariance answer =
        answerAt(frame, in_other_basin ? other_basin : Vector6d::Zero().eval());
    const PoseWithCovariance floored =
        scatter.floorAndAdd(frame * kFrameNs, odometryAt(frame), answer);
    if (frame < FixScatterOptions{}.min_answers || !in_other_basin) {
      continue;
    }
    ++wrong_answers;
    EXPECT_LT(normalizedErrorSquared(floored, truePose(frame)), kChi2SixDof9973) << frame;
  }
  EXPECT_GT(wrong_answers, 30);
}

// Answers as precise as they say, drawn from their own covariance, keep
// about it. A sample of 31 fluctuates: its whitened eigenvalues spread over
// (1 -+ sqrt(6 / 31))^2 = 0.31 to 2.1 (Marchenko and Pastur), and those above
// 1, about half, average about 1.4, so the variance grows by about a fifth
// and the sigma by a tenth on the typical answer, and by at most sqrt(2.1) =
// 1.45 along one direction.
TEST(FixScatter, BarelyRaisesAnswersAsPreciseAsTheySay) {
  std::mt19937 random(11);
  std::normal_distribution<double> unit;
  const Eigen::LLT<Matrix6d> cholesky(kAnswerCovariance);
  FixScatter scatter;
  std::vector<double> ratios;
  for (int frame = 0; frame < 600; ++frame) {
    Vector6d draw;
    for (double& value : draw) {
      value = unit(random);
    }
    const PoseWithCovariance answer = answerAt(frame, cholesky.matrixL() * draw);
    const PoseWithCovariance floored =
        scatter.floorAndAdd(frame * kFrameNs, odometryAt(frame), answer);
    ratios.push_back(positionSigmaRatio(floored.covariance, answer.covariance));
  }
  std::sort(ratios.begin(), ratios.end());
  EXPECT_LT(ratios[ratios.size() / 2], 1.2);
  EXPECT_LT(ratios[ratios.size() * 95 / 100], 1.45);
}

// Answers a second old, or of the robot's odometry before it restarted, say
// nothing about the pose now.
TEST(FixScatter, ForgetsAnswersOutsideItsWindowAndEpoch) {
  const Vector6d metre_off = (Vector6d() << 1.0, 0.0, 0.0, 0.0, 0.0, 0.0).finished();
  FixScatter scatter;
  for (int frame = 0; frame < 10; ++frame) {
    scatter.floorAndAdd(frame * kFrameNs, odometryAt(frame), answerAt(frame, metre_off));
  }
  const int later = 10 + static_cast<int>(FixScatterOptions{}.window_s * 30.0) + 1;
  const PoseWithCovariance after_the_window =
      scatter.floorAndAdd(later * kFrameNs, odometryAt(later), answerAt(later, Vector6d::Zero()));
  EXPECT_EQ(after_the_window.covariance, kAnswerCovariance);

  FixScatter restarted;
  for (int frame = 0; frame < 10; ++frame) {
    restarted.floorAndAdd(frame * kFrameNs, odometryAt(frame), answerAt(frame, metre_off));
  }
  OdometryPose new_epoch = odometryAt(10);
  ++new_epoch.epoch;
  EXPECT_EQ(
      restarted.floorAndAdd(10 * kFrameNs, new_epoch, answerAt(10, Vector6d::Zero())).covariance,
      kAnswerCovariance);
}

TEST(FixScatter, NeedsMinAnswersBeforeItRaisesAnything) {
  const Vector6d metre_off = (Vector6d() << 1.0, 0.0, 0.0, 0.0, 0.0, 0.0).finished();
  FixScatter scatter;
  const int min_answers = FixScatterOptions{}.min_answers;
  for (int frame = 0; frame < min_answers; ++frame) {
    const Vector6d error = frame % 2 == 0 ? metre_off : Vector6d::Zero().eval();
    EXPECT_EQ(
        scatter.floorAndAdd(frame * kFrameNs, odometryAt(frame), answerAt(frame, error)).covariance,
        kAnswerCovariance);
  }
  EXPECT_GT(positionSigmaRatio(scatter
                                   .floorAndAdd(min_answers * kFrameNs, odometryAt(min_answers),
                                                answerAt(min_answers, Vector6d::Zero()))
                                   .covariance,
                               kAnswerCovariance),
            5.0);
}

}  // namespace
}  // namespace lineloc
