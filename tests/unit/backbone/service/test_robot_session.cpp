// A robot's session on the backbone on LineSets of a robot driving down the
// synthetic street (street_drive.h): no database, no DDS.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <utility>

#include "backbone/service/robot_session.h"
#include "tests/unit/backbone/service/street_drive.h"

namespace lineloc {
namespace {

using namespace lineloc::testing;

// From a DGPS + compass start the session searches the robot's frames until
// it takes a hypothesis; the next frame is tracked from it, OK and within its
// covariance, with the hypothesis's unproven part; the proof search it asks
// for at once agrees with tracking.
TEST(RobotSession, SearchesFromADgpsStartThenTracksAndProvesTheTakenPose) {
  StreetDrive drive(makeStreet(), 7);
  const LocalizerOptions localizer;
  RobotSession session(RobotSessionOptions{}, localizer);
  std::optional<int> taken_at;
  for (int frame = 0; frame < 8 && !taken_at; ++frame) {
    Eigen::Isometry3d truth;
    const LineSetData line_set = drive.frame(frame, kSpeedMS, truth);
    const OdometryPose odometry = session.hear(line_set);
    const RobotSession::FramePlan plan = session.planFor(line_set, odometry, *drive.map());
    ASSERT_EQ(plan.plan, RobotSession::Plan::kSearch) << "frame " << frame;
    if (session.search(line_set, odometry, drive.map(), plan.prior, localizer).decision) {
      taken_at = frame;
    }
  }
  ASSERT_TRUE(taken_at) << "no hypothesis taken in 8 frames";

  Eigen::Isometry3d truth;
  const LineSetData line_set = drive.frame(*taken_at + 1, kSpeedMS, truth);
  const OdometryPose odometry = session.hear(line_set);
  const RobotSession::FramePlan plan = session.planFor(line_set, odometry, *drive.map());
  ASSERT_EQ(plan.plan, RobotSession::Plan::kTrack) << "carried from the taken hypothesis";
  EXPECT_EQ(plan.min_start_step_m, RobotSessionOptions{}.carried_start_step_m);
  LocalizerOptions from_hypothesis = localizer;
  from_hypothesis.min_start_step_m = plan.min_start_step_m;
  const Localization localization =
      localize(line_set.segments, line_set.corners, drive.map()->segments, drive.map()->scene,
               plan.prior, line_set.camera, from_hypothesis);
  PoseFixData fix;
  const RobotSession::Answered answered = session.answer(line_set, odometry, localization, fix);
  ASSERT_EQ(fix.status, lineloc_msg_FIX_OK);
  EXPECT_LT(normalizedErrorSquared(fix.T_world_camera, truth), kChi2Six999);
  EXPECT_GE(fix.unproven_position_sigma_m, localizer.acquisition.acquired_position_sigma_m);
  EXPECT_FALSE(answered.started_from_prediction);
  ASSERT_TRUE(answered.proof_due) << "the first proof search is due at once";

  const RobotSession::Proved proved = session.prove(line_set, *drive.map(), fix.T_world_camera.pose,
                                                    *answered.proof_due, localizer);
  EXPECT_TRUE(proved.applied);
  EXPECT_EQ(proved.verdict.proof, Proof::kAgrees) << proved.verdict.outcome;
}

// A frame whose prediction is narrow enough is tracked from it, and its first
// OK answer starts tracking from the robot's own prediction.
// A robot searched for on one backbone: the handover it leaves holds its
// acquisition's hypotheses, and a session taking it over that is offered
// that handover aligns them in its first search.
TEST(RobotSession, ARobotTakenOverWhileSearchedForCarriesItsHypothesesIntoTheSearch) {
  StreetDrive drive(makeStreet(), 7);
  const LocalizerOptions localizer;
  const auto searchFrame = [&](RobotSession& session, int frame, Eigen::Isometry3d& truth) {
    const LineSetData line_set = drive.frame(frame, kSpeedMS, truth);
    const OdometryPose odometry = session.hear(line_set);
    const RobotSession::FramePlan plan = session.planFor(line_set, odometry, *drive.map());
    EXPECT_EQ(plan.plan, RobotSession::Plan::kSearch) << "frame " << frame;
    AcquisitionSession::Searched searched =
        session.search(line_set, odometry, drive.map(), plan.prior, localizer);
    return std::pair(searched, session.handover(line_set.stamp_ns, odometry));
  };
  RobotSession before(RobotSessionOptions{}, localizer);
  Eigen::Isometry3d truth;
  const TrackingHandover left = searchFrame(before, 0, truth).second;
  EXPECT_FALSE(left.tracking);
  ASSERT_FALSE(left.hypotheses.T_prediction_camera.empty());

  RobotSession after(RobotSessionOptions{}, localizer);
  ASSERT_TRUE(after.awaitsHandover());
  after.offerHandover(left);
  const AcquisitionSession::Searched first = searchFrame(after, 1, truth).first;
  EXPECT_TRUE(std::ranges::any_of(
      first.acquisition.summary.aligned_hypotheses, [&](const ScoredHypothesis& hypothesis) {
        return hypothesis.carried_index >= 0 &&
               (hypothesis.T_world_camera.pose.translation() - truth.translation()).norm() < 0.3;
      }));
}

TEST(RobotSession, TracksANarrowPredictionAndStartsProvingIt) {
  StreetDrive drive(makeStreet(), 3);
  const LocalizerOptions localizer;
  RobotSession session(RobotSessionOptions{}, localizer);
  Eigen::Isometry3d truth;
  LineSetData line_set = drive.frame(0, 0.0, truth);
  line_set.predicted_T_world_camera = {truth, diagonalPoseCovariance(0.05, 0.2 * M_PI / 180.0)};
  const OdometryPose odometry = session.hear(line_set);
  const RobotSession::FramePlan plan = session.planFor(line_set, odometry, *drive.map());
  ASSERT_EQ(plan.plan, RobotSession::Plan::kTrack);
  EXPECT_EQ(plan.min_start_step_m, 0.0);
  const Localization localization =
      localize(line_set.segments, line_set.corners, drive.map()->segments, drive.map()->scene,
               plan.prior, line_set.camera, localizer);
  PoseFixData fix;
  const RobotSession::Answered answered = session.answer(line_set, odometry, localization, fix);
  ASSERT_EQ(fix.status, lineloc_msg_FIX_OK);
  EXPECT_TRUE(answered.started_from_prediction);
  EXPECT_EQ(fix.unproven_position_sigma_m, TrackingProofOptions{}.proof_position_sigma_m);
  EXPECT_TRUE(answered.proof_due);
}

}  // namespace
}  // namespace lineloc
