// The proof of a robot's tracking: the unproven part of its fixes, when proof
// searches are due, and what their verdicts do.
#include <gtest/gtest.h>

#include <cmath>

#include "backbone/service/tracking_proof.h"

namespace lineloc {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The robot's odometry `forward_m` along the camera's axis from the origin.
OdometryPose movedOn(double forward_m, uint64_t epoch = 0) {
  OdometryPose odometry;
  odometry.T_odom_camera.translation() = Eigen::Vector3d(0.0, 0.0, forward_m);
  odometry.epoch = epoch;
  return odometry;
}

PoseWithCovariance fixAt(double forward_m) {
  PoseWithCovariance fix{Eigen::Isometry3d::Identity(), diagonalPoseCovariance(0.01, 0.001)};
  fix.pose.translation() = Eigen::Vector3d(0.0, 0.0, forward_m);
  return fix;
}

int64_t stampAt(double t_s) {
  return static_cast<int64_t>(t_s * 1e9);
}

ProofVerdict agreeing() {
  return {Proof::kAgrees, "", {}, true};
}

TEST(TrackingProof, ARobotTrackedFromItsPredictionIsProvenByTwoAgreeingProofsFromElsewhere) {
  const TrackingProofOptions options;
  const LocalizerOptions localizer;
  TrackingProof proof(options, localizer);

  TrackingProof::Unproven first = proof.unprovenAt(stampAt(0.0), movedOn(0.0), fixAt(0.0));
  EXPECT_TRUE(first.started_from_prediction);
  ASSERT_TRUE(first.offset);
  EXPECT_EQ(first.offset->position_m, options.proof_position_sigma_m) << "before any proof";
  EXPECT_EQ(first.offset->rotation_rad, options.confirm_rotation_rad);
  ASSERT_TRUE(first.proof_due) << "the first proof search is due at once";

  ASSERT_TRUE(proof.apply(agreeing(), *first.proof_due));
  const TrackingProof::Unproven looked = proof.unprovenAt(stampAt(0.1), movedOn(0.5), fixAt(0.5));
  EXPECT_FALSE(looked.started_from_prediction);
  ASSERT_TRUE(looked.offset);
  EXPECT_EQ(looked.offset->position_m, localizer.acquisition.acquired_position_sigma_m)
      << "looked around: only the search's resolution remains";
  EXPECT_FALSE(looked.proof_due) << "the next is due acquisition_proven_after_m on";

  for (double moved_m : {options.acquisition_proven_after_m,
                         options.acquisition_proven_after_m + options.proof_retry_m}) {
    const TrackingProof::Unproven due =
        proof.unprovenAt(stampAt(moved_m), movedOn(moved_m), fixAt(moved_m));
    ASSERT_TRUE(due.offset) << moved_m << " m";
    ASSERT_TRUE(due.proof_due) << moved_m << " m";
    ASSERT_TRUE(proof.apply(agreeing(), *due.proof_due));
  }
  EXPECT_FALSE(proof.unprovenAt(stampAt(5.0), movedOn(3.0), fixAt(3.0)).offset) << "proven";
}

TEST(TrackingProof, AProofAtTheStartItselfCountsAsLookingAroundNotAsProof) {
  TrackingProofOptions options;
  options.agreeing_proofs_needed = 1;
  TrackingProof proof(options, LocalizerOptions{});
  const TrackingProof::Unproven first = proof.unprovenAt(0, movedOn(0.0), fixAt(0.0));
  ASSERT_TRUE(proof.apply(agreeing(), *first.proof_due));
  EXPECT_TRUE(proof.unprovenAt(1, movedOn(0.2), fixAt(0.2)).offset);
}

TEST(TrackingProof, ARivalAProofFindsWidensTheFixesUntilProven) {
  TrackingProof proof(TrackingProofOptions{}, LocalizerOptions{});
  const TrackingProof::Unproven first = proof.unprovenAt(0, movedOn(0.0), fixAt(0.0));
  ASSERT_TRUE(proof.apply({Proof::kUndecided, "", {1.2, 0.4 * kDeg}, true}, *first.proof_due));
  const TrackingProof::Unproven next = proof.unprovenAt(1, movedOn(0.1), fixAt(0.1));
  ASSERT_TRUE(next.offset);
  EXPECT_EQ(next.offset->position_m, 1.2);
}

TEST(TrackingProof, AContradictingProofEndsTrackingAndWidensTheRobotsSearch) {
  const TrackingProofOptions options;
  TrackingProof proof(options, LocalizerOptions{});
  const TrackingProof::Unproven first = proof.unprovenAt(0, movedOn(0.0), fixAt(0.0));
  const PoseWithCovariance narrow{Eigen::Isometry3d::Identity(),
                                  diagonalPoseCovariance(0.05, 0.1 * kDeg)};
  EXPECT_EQ(proof.searchPrior(narrow).covariance, narrow.covariance);

  ASSERT_TRUE(proof.apply({Proof::kContradicts, "", {}, true}, *first.proof_due));
  const PoseWithCovariance widened = proof.searchPrior(narrow);
  EXPECT_DOUBLE_EQ(widened.covariance(0, 0),
                   options.proof_position_sigma_m * options.proof_position_sigma_m);
  EXPECT_DOUBLE_EQ(widened.covariance(1, 1),
                   options.proof_position_sigma_m * options.proof_position_sigma_m);
  EXPECT_DOUBLE_EQ(widened.covariance(2, 2), narrow.covariance(2, 2));
  EXPECT_TRUE(proof.unprovenAt(1, movedOn(0.1), fixAt(0.1)).started_from_prediction);
}

TEST(TrackingProof, AVerdictOnAStartTheRobotNoLongerTracksFromIsDropped) {
  TrackingProof proof(TrackingProofOptions{}, LocalizerOptions{});
  const TrackingProof::Unproven old_start = proof.unprovenAt(0, movedOn(0.0), fixAt(0.0));
  // The robot restarted: a new odometry epoch starts tracking anew.
  const TrackingProof::Unproven new_start =
      proof.unprovenAt(stampAt(1.0), movedOn(0.0, 1), fixAt(0.0));
  ASSERT_TRUE(new_start.started_from_prediction);
  EXPECT_FALSE(proof.apply({Proof::kContradicts, "", {}, true}, *old_start.proof_due));
  EXPECT_FALSE(proof.unprovenAt(stampAt(1.1), movedOn(0.1, 1), fixAt(0.1)).started_from_prediction)
      << "the new start still stands";
}

// A hypothesis taken at 2 s, 0.8 m wide and with a rival 1.5 m off: the next
// second's frames are tracked from it moved by the robot's odometry and
// narrowed to tracking's limits, and its width and rival stay unproven.
TEST(TrackingProof, ATakenHypothesisIsCarriedForCarrySearchS) {
  const TrackingProofOptions options;
  const LocalizerOptions localizer;
  TrackingProof proof(options, localizer);
  HypothesisDecision decision;
  decision.hypothesis.T_world_camera = {Eigen::Isometry3d::Identity(),
                                        diagonalPoseCovariance(0.8, 0.2 * kDeg)};
  decision.covered = {1.5, 0.5 * kDeg};
  proof.startFromSearch(stampAt(2.0), movedOn(0.0), decision);

  const std::optional<PoseWithCovariance> carried = proof.carriedStart(stampAt(2.5), movedOn(0.6));
  ASSERT_TRUE(carried);
  EXPECT_NEAR(carried->pose.translation().z(), 0.6, 1e-12);
  EXPECT_FALSE(needsAcquisition(*carried, localizer)) << "narrowed to tracking's limits";
  EXPECT_FALSE(proof.carriedStart(stampAt(2.0), movedOn(0.0))) << "its own frame";
  EXPECT_FALSE(proof.carriedStart(stampAt(2.0 + options.carry_search_s + 0.1), movedOn(1.0)));
  EXPECT_FALSE(proof.carriedStart(stampAt(2.5), movedOn(0.6, 1))) << "another odometry epoch";

  const TrackingProof::Unproven unproven = proof.unprovenAt(stampAt(2.5), movedOn(0.6), *carried);
  EXPECT_FALSE(unproven.started_from_prediction);
  ASSERT_TRUE(unproven.offset);
  EXPECT_NEAR(unproven.offset->position_m, 1.5, 1e-12);
}

// A prediction as narrow as a tracked robot's: 2 cm, 0.05 degree.
PoseWithCovariance narrowPredictionAt(double forward_m) {
  PoseWithCovariance predicted = fixAt(forward_m);
  predicted.covariance = diagonalPoseCovariance(0.02, 0.05 * kDeg);
  return predicted;
}

// Proven on one backbone at 3 m of motion, tracking is handed over: another
// backbone's first OK fix, with the robot's prediction narrow and agreeing,
// continues it proven, with no proof search due.
TEST(TrackingProof, AProvenRobotHandedOverStaysProvenWithoutAProofSearch) {
  const TrackingProofOptions options;
  TrackingProof first(options, LocalizerOptions{});
  for (double moved_m : {0.0, 1.0, 2.0}) {
    const TrackingProof::Unproven due =
        first.unprovenAt(stampAt(moved_m), movedOn(moved_m), fixAt(moved_m));
    ASSERT_TRUE(due.proof_due) << moved_m << " m";
    ASSERT_TRUE(first.apply(agreeing(), *due.proof_due));
  }
  EXPECT_FALSE(first.unprovenAt(stampAt(3.0), movedOn(3.0), fixAt(3.0)).offset);
  const TrackingHandover handover = first.handover(stampAt(3.0), movedOn(3.0));
  EXPECT_TRUE(handover.tracking);
  EXPECT_EQ(handover.agreeing_proofs, 2);

  // The next backbone's odometry chain starts at its first frame.
  TrackingProof next(options, LocalizerOptions{});
  ASSERT_TRUE(
      next.resume(handover, stampAt(4.0), movedOn(0.0, 7), fixAt(4.0), narrowPredictionAt(4.01)));
  const TrackingProof::Unproven unproven =
      next.unprovenAt(stampAt(4.0), movedOn(0.0, 7), fixAt(4.0));
  EXPECT_FALSE(unproven.started_from_prediction);
  EXPECT_FALSE(unproven.offset);
  EXPECT_FALSE(unproven.proof_due);
  EXPECT_EQ(next.handover(stampAt(4.0), movedOn(0.0, 7)).agreeing_proofs, 2);
}

// An unproven robot handed over keeps its rival and the motion left to its
// next proof search.
TEST(TrackingProof, AnUnprovenRobotHandedOverKeepsItsRivalAndItsNextProofsDistance) {
  const TrackingProofOptions options;
  TrackingProof first(options, LocalizerOptions{});
  const TrackingProof::Unproven start = first.unprovenAt(stampAt(0.0), movedOn(0.0), fixAt(0.0));
  ASSERT_TRUE(first.apply({Proof::kUndecided, "", {1.2, 0.4 * kDeg}, true}, *start.proof_due));
  const TrackingHandover handover = first.handover(stampAt(0.4), movedOn(0.4));
  EXPECT_NEAR(handover.proof_due_in_m, options.acquisition_proven_after_m - 0.4, 1e-12);

  TrackingProof next(options, LocalizerOptions{});
  ASSERT_TRUE(
      next.resume(handover, stampAt(0.5), movedOn(0.0), fixAt(0.5), narrowPredictionAt(0.5)));
  const TrackingProof::Unproven resumed = next.unprovenAt(stampAt(0.5), movedOn(0.0), fixAt(0.5));
  ASSERT_TRUE(resumed.offset);
  EXPECT_EQ(resumed.offset->position_m, 1.2);
  EXPECT_FALSE(resumed.proof_due);
  const double due_m = options.acquisition_proven_after_m - 0.4;
  EXPECT_FALSE(next.unprovenAt(stampAt(0.6), movedOn(due_m - 0.05), fixAt(0.6)).proof_due);
  EXPECT_TRUE(next.unprovenAt(stampAt(0.7), movedOn(due_m + 0.05), fixAt(0.7)).proof_due);
}

// A handover is not continued, and tracking is proven from the start, when
// the robot was not tracked, the handover is not older than the fix, the
// robot's prediction is wide (its dead reckoning may have left the handed-over
// basin) or disagrees with the fix, or tracking here has as many agreeing
// proofs already.
TEST(TrackingProof, AHandoverIsContinuedOnlyFromANarrowAgreeingPredictionOfAnUntrackedRobot) {
  const TrackingProofOptions options;
  TrackingProof first(options, LocalizerOptions{});
  EXPECT_FALSE(first.handover(stampAt(0.0), movedOn(0.0)).tracking) << "no start yet";
  first.unprovenAt(stampAt(0.0), movedOn(0.0), fixAt(0.0));
  const TrackingHandover handover = first.handover(stampAt(1.0), movedOn(1.0));
  ASSERT_TRUE(handover.tracking);

  TrackingHandover untracked = handover;
  untracked.tracking = false;
  PoseWithCovariance wide_position = narrowPredictionAt(2.0);
  wide_position.covariance(1, 1) = std::pow(options.confirm_position_m / 2.0, 2);
  PoseWithCovariance wide_rotation = narrowPredictionAt(2.0);
  wide_rotation.covariance(5, 5) = std::pow(options.confirm_rotation_rad / 2.0, 2);
  const PoseWithCovariance beside = narrowPredictionAt(2.0 + 2.0 * options.confirm_position_m);
  struct Case {
    const char* what;
    TrackingHandover handover;
    int64_t stamp_ns;
    PoseWithCovariance predicted;
  };
  for (const Case& refused : {Case{"not tracked", untracked, stampAt(2.0), narrowPredictionAt(2.0)},
                              Case{"not older", handover, stampAt(1.0), narrowPredictionAt(2.0)},
                              Case{"wide position", handover, stampAt(2.0), wide_position},
                              Case{"wide rotation", handover, stampAt(2.0), wide_rotation},
                              Case{"disagreeing", handover, stampAt(2.0), beside}}) {
    TrackingProof next(options, LocalizerOptions{});
    EXPECT_FALSE(next.resume(refused.handover, refused.stamp_ns, movedOn(0.0), fixAt(2.0),
                             refused.predicted))
        << refused.what;
    EXPECT_TRUE(next.unprovenAt(refused.stamp_ns, movedOn(0.0), fixAt(2.0)).started_from_prediction)
        << refused.what;
  }
  TrackingProof tracking(options, LocalizerOptions{});
  tracking.unprovenAt(stampAt(1.5), movedOn(0.0), fixAt(1.5));
  EXPECT_FALSE(
      tracking.resume(handover, stampAt(2.0), movedOn(0.5), fixAt(2.0), narrowPredictionAt(2.0)))
      << "tracked here already, with as many proofs";
}

// A backbone that started tracking a robot from its prediction before the
// other's handover reached it (one restarted, taking its robots back)
// continues from the handover once it comes, as it states more proof.
TEST(TrackingProof, AHandoverWithMoreProofReplacesAStartFromThePrediction) {
  const TrackingProofOptions options;
  TrackingProof here(options, LocalizerOptions{});
  ASSERT_TRUE(here.unprovenAt(stampAt(1.0), movedOn(0.0), fixAt(1.0)).started_from_prediction);
  TrackingHandover proven = here.handover(stampAt(0.9), movedOn(0.0));
  proven.agreeing_proofs = options.agreeing_proofs_needed;
  EXPECT_FALSE(here.proven());
  ASSERT_TRUE(here.resume(proven, stampAt(1.1), movedOn(0.1), fixAt(1.1), narrowPredictionAt(1.1)));
  EXPECT_TRUE(here.proven());
  EXPECT_FALSE(here.unprovenAt(stampAt(1.1), movedOn(0.1), fixAt(1.1)).offset);
}

}  // namespace
}  // namespace lineloc
