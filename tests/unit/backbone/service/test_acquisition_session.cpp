// The robot's acquisition session on LineSets of a robot driving down the
// synthetic street (street_drive.h): no database, no DDS.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <utility>

#include "backbone/service/acquisition_session.h"
#include "tests/unit/backbone/service/street_drive.h"

namespace lineloc {
namespace {

using namespace lineloc::testing;

// The street's frames searched by a session.
class DriveOn {
 public:
  DriveOn(Street street, uint32_t seed) : drive_(std::move(street), seed) {}

  // Searches `frame` of a drive at `speed_m_s` in `session`; its true pose in `truth`.
  AcquisitionSession::Searched search(AcquisitionSession& session, int frame, double speed_m_s,
                                      Eigen::Isometry3d& truth) {
    const LineSetData line_set = drive_.frame(frame, speed_m_s, truth);
    return session.search(line_set, odometryAt(truth), drive_.map(),
                          line_set.predicted_T_world_camera, LocalizerOptions{});
  }

 private:
  StreetDrive drive_;
};

TEST(AcquisitionSession, TakesTheCameraWithinAFewFramesOfADgpsStart) {
  DriveOn drive(makeStreet(), 7);
  AcquisitionSession session;
  for (int frame = 0; frame < 8; ++frame) {
    Eigen::Isometry3d truth;
    const AcquisitionSession::Searched searched = drive.search(session, frame, kSpeedMS, truth);
    if (!searched.decision) {
      EXPECT_GT(searched.hypotheses, 0u) << "frame " << frame;
      continue;
    }
    EXPECT_GE(frame, 1) << "one frame is no evidence";
    const PoseWithCovariance& taken = searched.decision->hypothesis.T_world_camera;
    EXPECT_LT(normalizedErrorSquared(taken, truth), kChi2Six999);
    EXPECT_LT((taken.pose.translation() - truth.translation()).norm(), 0.3);
    return;
  }
  ADD_FAILURE() << "no hypothesis taken in 8 frames";
}

TEST(AcquisitionSession, ARobotDrivingAlongAFeaturelessFacadeIsNeverTaken) {
  Street wall;
  addBox(wall, 8, -50, 9, 200, 10);  // nothing to place the camera along it
  DriveOn drive(wall, 9);
  AcquisitionSession session;
  for (int frame = 0; frame < 8; ++frame) {
    Eigen::Isometry3d truth;
    EXPECT_FALSE(drive.search(session, frame, kSpeedMS, truth).decision.has_value())
        << "frame " << frame;
  }
}

// The frames of the drive from `first` on searched by `session` until one is
// taken or `frames` have been; returns the number searched.
int searchUntilTaken(DriveOn& drive, AcquisitionSession& session, int first, int frames) {
  for (int frame = first; frame < first + frames; ++frame) {
    Eigen::Isometry3d truth;
    if (drive.search(session, frame, kSpeedMS, truth).decision) {
      return frame - first + 1;
    }
  }
  return frames + 1;
}

// A backbone taking the robot over after another's first searched frame:
// its first search aligns the other's hypotheses, moved to its frame by the
// robot's predictions, among them the truth; it takes none on that one frame
// (they bring no evidence), and takes the camera no later than a session
// that starts afresh.
TEST(AcquisitionSession, ASessionTakingTheRobotOverCarriesTheOthersHypothesesIn) {
  DriveOn drive(makeStreet(), 7);
  AcquisitionSession before;
  Eigen::Isometry3d truth;
  ASSERT_FALSE(drive.search(before, 0, kSpeedMS, truth).decision);
  const HandedHypotheses handed = before.handed();
  ASSERT_FALSE(handed.T_prediction_camera.empty());

  AcquisitionSession after;
  after.adopt(handed);
  const AcquisitionSession::Searched first = drive.search(after, 1, kSpeedMS, truth);
  EXPECT_FALSE(first.decision) << "handed hypotheses bring no evidence of their own";
  const std::vector<ScoredHypothesis>& aligned = first.acquisition.summary.aligned_hypotheses;
  EXPECT_TRUE(std::ranges::any_of(aligned, [&](const ScoredHypothesis& hypothesis) {
    return hypothesis.carried_index >= 0 &&
           (hypothesis.T_world_camera.pose.translation() - truth.translation()).norm() < 0.3;
  })) << "the truth, carried from the other session";

  AcquisitionSession afresh;
  EXPECT_LE(searchUntilTaken(drive, after, 2, 8), searchUntilTaken(drive, afresh, 1, 8) - 1);
}

TEST(AcquisitionSession, HandedHypothesesOlderThanItsWindowAreNotCarried) {
  DriveOn drive(makeStreet(), 7);
  AcquisitionSession before;
  Eigen::Isometry3d truth;
  drive.search(before, 0, kSpeedMS, truth);
  HandedHypotheses handed = before.handed();
  handed.stamp_ns -= static_cast<int64_t>((HypothesisSetOptions{}.window_s + 1.0) * 1e9);
  AcquisitionSession after;
  after.adopt(handed);
  const AcquisitionSession::Searched first = drive.search(after, 1, kSpeedMS, truth);
  EXPECT_TRUE(std::ranges::none_of(
      first.acquisition.summary.aligned_hypotheses,
      [](const ScoredHypothesis& hypothesis) { return hypothesis.carried_index >= 0; }));
  after.clear();
  EXPECT_TRUE(after.handed().T_prediction_camera.empty()) << "cleared";
}

TEST(AcquisitionSession, StartsAfreshOnceCleared) {
  DriveOn drive(makeStreet(), 11);
  AcquisitionSession session;
  Eigen::Isometry3d truth;
  drive.search(session, 0, 0.0, truth);
  session.clear();
  EXPECT_FALSE(drive.search(session, 1, 0.0, truth).decision) << "its first frame again";
}

}  // namespace
}  // namespace lineloc
