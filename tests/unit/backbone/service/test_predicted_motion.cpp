// The robot's own motion read from its predictions, its filter's corrections
// left out.
#include <gtest/gtest.h>

#include "backbone/service/predicted_motion.h"

namespace lineloc {
namespace {

constexpr int64_t kFrameNs = 33'333'333;

using Vector6d = Eigen::Matrix<double, 6, 1>;

// A robot driving at a constant velocity and turn rate, camera frame: each
// frame moves the camera by kStep.
const Eigen::Isometry3d kStep = [] {
  Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
  step.linear() =
      Eigen::AngleAxisd(0.004, Eigen::Vector3d(0.1, -1.0, 0.05).normalized()).toRotationMatrix();
  step.translation() = Eigen::Vector3d(0.02, 0.001, 0.3);
  return step;
}();

Eigen::Isometry3d truePose(int frame) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(85.0, -30.0, 1.6);
  for (int i = 0; i < frame; ++i) {
    pose = pose * kStep;
  }
  return pose;
}

// The prediction of a dead-reckoning robot: the truth, its covariance growing.
PoseWithCovariance predictionAt(int frame) {
  return {truePose(frame), diagonalPoseCovariance(3.0 + 0.001 * frame, 0.02 + 1e-5 * frame)};
}

// The odometry's motion from frame 0 to `frame` against the truth's.
void expectTrueMotion(const Eigen::Isometry3d& odometry_motion, int frame) {
  const Eigen::Isometry3d true_motion = truePose(0).inverse() * truePose(frame);
  EXPECT_LT((odometry_motion.translation() - true_motion.translation()).norm(), 1e-9);
  EXPECT_LT(Eigen::AngleAxisd(odometry_motion.linear().transpose() * true_motion.linear()).angle(),
            1e-9);
}

// The same from two odometry poses, which must be of one epoch.
void expectMotionOfTruth(const OdometryPose& first, const OdometryPose& later, int frame) {
  EXPECT_EQ(later.epoch, first.epoch);
  expectTrueMotion(first.T_odom_camera.inverse() * later.T_odom_camera, frame);
}

TEST(PredictedMotion, FollowsThePredictionWhileNothingCorrectsIt) {
  PredictedMotion motion;
  const OdometryPose first = motion.add(0, predictionAt(0));
  OdometryPose last = first;
  for (int frame = 1; frame <= 30; ++frame) {
    last = motion.add(frame * kFrameNs, predictionAt(frame));
  }
  expectMotionOfTruth(first, last, 30);
}

TEST(PredictedMotion, LeavesOutTheJumpOfACorrection) {
  PredictedMotion motion;
  const OdometryPose first = motion.add(0, predictionAt(0));
  for (int frame = 1; frame <= 10; ++frame) {
    motion.add(frame * kFrameNs, predictionAt(frame));
  }
  // A DGPS fix moves the prediction 1.5 m and shrinks its covariance from
  // 3 m to 2.5 m; from then on the prediction carries the offset.
  Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
  offset.translation() = Eigen::Vector3d(1.2, -0.9, 0.0);
  OdometryPose last = first;
  for (int frame = 11; frame <= 20; ++frame) {
    PoseWithCovariance corrected = predictionAt(frame);
    corrected.pose = offset * corrected.pose;
    corrected.covariance.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() * 2.5 * 2.5;
    last = motion.add(frame * kFrameNs, corrected);
  }
  expectMotionOfTruth(first, last, 20);
}

// The odometry's motion over frames 0 to 2 when an update moved frame 2's
// prediction by `correction` (applied in the world frame) and lowered its
// covariance's diagonal below frame 1's by `variance_drop`.
Eigen::Isometry3d motionOverAnUpdate(const Eigen::Isometry3d& correction,
                                     const Vector6d& variance_drop) {
  PredictedMotion motion;
  const OdometryPose first = motion.add(0, predictionAt(0));
  motion.add(kFrameNs, predictionAt(1));
  PoseWithCovariance updated{correction * truePose(2), predictionAt(1).covariance};
  updated.covariance.diagonal() -= variance_drop;
  return first.T_odom_camera.inverse() * motion.add(2 * kFrameNs, updated).T_odom_camera;
}

TEST(PredictedMotion, LeavesOutACompassCorrectionOfTheHeading) {
  // The heading turned by 1 degree while the rotation variance's trace
  // dropped by twice max_correction_rad^2.
  const double max_correction_rad = PredictedMotionOptions{}.max_correction_rad;
  Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
  turn.linear() = Eigen::AngleAxisd(M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Vector6d drop = Vector6d::Zero();
  drop[5] = 2.0 * max_correction_rad * max_correction_rad;
  expectTrueMotion(motionOverAnUpdate(turn, drop), 2);
}

TEST(PredictedMotion, TakesAnUpdateThatMovesThePredictionByMillimetresAsMotion) {
  // The position variance's trace dropped by a quarter of max_correction_m^2;
  // the 2 mm it moved are kept.
  const double max_correction_m = PredictedMotionOptions{}.max_correction_m;
  Eigen::Isometry3d shift = Eigen::Isometry3d::Identity();
  shift.translation().x() = 0.002;
  Vector6d drop = Vector6d::Zero();
  drop[0] = 0.25 * max_correction_m * max_correction_m;
  const Eigen::Vector3d true_motion = (truePose(0).inverse() * truePose(2)).translation();
  EXPECT_NEAR((motionOverAnUpdate(shift, drop).translation() - true_motion).norm(), 0.002, 1e-9);
}

TEST(PredictedMotion, AFrameOlderThanTheLastStartsANewEpoch) {
  PredictedMotion motion;
  const OdometryPose first = motion.add(10 * kFrameNs, predictionAt(0));
  EXPECT_EQ(motion.add(11 * kFrameNs, predictionAt(1)).epoch, first.epoch);
  // The robot restarted: its frames begin again.
  const OdometryPose restarted = motion.add(kFrameNs, predictionAt(5));
  EXPECT_EQ(restarted.epoch, first.epoch + 1);
  EXPECT_TRUE(restarted.T_odom_camera.isApprox(predictionAt(5).pose));
  expectMotionOfTruth(restarted, motion.add(2 * kFrameNs, predictionAt(6)), 1);
}

}  // namespace
}  // namespace lineloc
