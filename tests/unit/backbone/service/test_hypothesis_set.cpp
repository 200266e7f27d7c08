// The acquisition's estimator over several frames on a street of made-up
// scores: each frame says which poses its view fits and how well, so that
// what the estimator takes, and when, follows from the evidence alone.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "backbone/service/hypothesis_set.h"

namespace lineloc {
namespace {

// A camera pose in the world (axes aligned with the world's: the robot's
// motion in its own frame is the motion in the world).
Eigen::Isometry3d at(double x_m, double y_m) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x_m, y_m, 1.5);
  return pose;
}

// A pose a view fits, and how well: its verification score and inliers.
struct Fit {
  Eigen::Isometry3d T_world_camera;
  double score = 0.0;
  int inliers = 20;
};

// One frame of a robot driving north: its odometry (metres driven), what
// its search's grid proposes, and every pose its view fits (which a start
// near one aligns to).
struct Frame {
  double driven_m = 0.0;
  std::vector<Fit> proposed;
  std::vector<Fit> fits;
  uint64_t epoch = 0;
};

ScoredHypothesis scored(const Fit& fit, int carried_index) {
  return {{fit.T_world_camera, diagonalPoseCovariance(0.05, 0.003)},
          AlignmentStatus::kOk,
          fit.inliers,
          fit.score,
          carried_index};
}

// The fit a start within a search's reach of it aligns to.
std::optional<ScoredHypothesis> alignedFrom(const Frame& frame, const Eigen::Isometry3d& start,
                                            int carried_index) {
  for (const Fit& fit : frame.fits) {
    if ((fit.T_world_camera.translation() - start.translation()).norm() < 0.3) {
      return scored(fit, carried_index);
    }
  }
  return std::nullopt;
}

const auto kTrackable = [](const PoseWithCovariance&) { return true; };
constexpr int kMinInliers = 13;

// Feeds frames to a set as the backbone's searches do.
class Robot {
 public:
  explicit Robot(const HypothesisSetOptions& options = {}) : set_(options) {}

  // Adds `frame`, 0.5 s after the last one; the decision after it.
  std::optional<HypothesisDecision> see(
      const Frame& frame,
      const std::function<bool(const PoseWithCovariance&)>& trackable = kTrackable) {
    const uint64_t id = frames_.size();
    frames_.push_back(frame);
    OdometryPose odometry;
    odometry.T_odom_camera.translation() = Eigen::Vector3d(0.0, frame.driven_m, 0.0);
    odometry.epoch = frame.epoch;
    std::vector<ScoredHypothesis> aligned;
    for (const Fit& fit : frame.proposed) {
      aligned.push_back(scored(fit, -1));
    }
    const std::vector<Eigen::Isometry3d> carried = set_.carriedStarts(odometry);
    for (size_t i = 0; i < carried.size(); ++i) {
      if (auto found = alignedFrom(frame, carried[i], static_cast<int>(i))) {
        aligned.push_back(*found);
      }
    }
    set_.add({id, static_cast<int64_t>(id) * 500'000'000, odometry}, aligned,
             [&](uint64_t frame_id, const Eigen::Isometry3d& start) {
               rescored_frames_.push_back(frame_id);
               return alignedFrom(frames_.at(frame_id), start, -1);
             });
    return set_.decision(kMinInliers, trackable, &undecided_);
  }

  // Why the last decision took none.
  const std::string& undecided() const { return undecided_; }

  const HypothesisSet& set() const { return set_; }
  const std::vector<uint64_t>& rescoredFrames() const { return rescored_frames_; }

 private:
  HypothesisSet set_;
  std::vector<Frame> frames_;
  std::string undecided_;
  std::vector<uint64_t> rescored_frames_;
};

// The truth at x = 0, `driven_m` north of y = 20; a pose that fits as well
// `offset_m` further north.
Eigen::Isometry3d truthAfter(double driven_m) {
  return at(0.0, 20.0 + driven_m);
}

Frame standingBeforeTwoFits(double truth_score, double rival_score, double rival_offset_m) {
  const std::vector<Fit> fits = {{truthAfter(0.0), truth_score},
                                 {at(0.0, 20.0 + rival_offset_m), rival_score}};
  return {0.0, fits, fits};
}

// Driven `driven_m`: only the truth fits.
Frame movedOn(double driven_m, double truth_score = 15.0) {
  const std::vector<Fit> fits = {{truthAfter(driven_m), truth_score}};
  return {driven_m, fits, fits};
}

void expectAtTruth(const std::optional<HypothesisDecision>& decision, double driven_m) {
  ASSERT_TRUE(decision.has_value());
  EXPECT_LT(
      (decision->hypothesis.T_world_camera.pose.translation() - truthAfter(driven_m).translation())
          .norm(),
      1e-9);
  EXPECT_GE(decision->posterior, HypothesisSetOptions{}.min_posterior);
}

TEST(HypothesisSet, AStandingRobotWhoseViewFitsTwoPosesStaysUndecided) {
  Robot robot;
  for (int frame = 0; frame < 20; ++frame) {
    EXPECT_FALSE(robot.see(standingBeforeTwoFits(15.0, 14.0, 1.6))) << "frame " << frame;
  }
  EXPECT_EQ(robot.set().size(), 2u);
  EXPECT_EQ(robot.set().windowFrames(), std::vector<uint64_t>{0}) << "one view";
  EXPECT_NE(robot.undecided().find("is not likely enough"), std::string::npos) << robot.undecided();
}

TEST(HypothesisSet, TakesTheTruthOnceTheRobotHasMovedPastAViewThatFitsTwoPoses) {
  Robot robot;
  for (int frame = 0; frame < 4; ++frame) {
    EXPECT_FALSE(robot.see(standingBeforeTwoFits(15.0, 14.0, 1.6)));
  }
  // A view further on, where the rival, moved by the robot's motion, fits no longer.
  expectAtTruth(robot.see(movedOn(0.6)), 0.6);
}

TEST(HypothesisSet, OneViewThatTellsThePosesApartIsTakenOnItsSecondFrame) {
  Robot robot;
  EXPECT_FALSE(robot.see(standingBeforeTwoFits(25.0, 12.0, 1.6))) << "one frame is no evidence";
  const std::optional<HypothesisDecision> decision =
      robot.see(standingBeforeTwoFits(25.0, 12.0, 1.6));
  expectAtTruth(decision, 0.0);
  EXPECT_EQ(decision->covered.position_m, 0.0) << "the rival is unlikely";
}

TEST(HypothesisSet, TheAnswerCoversTheRivalsThatRemainLikely) {
  Robot robot;
  robot.see(standingBeforeTwoFits(20.0, 13.0, 1.0));
  const std::optional<HypothesisDecision> decision =
      robot.see(standingBeforeTwoFits(20.0, 13.0, 1.0));
  expectAtTruth(decision, 0.0);
  EXPECT_NEAR(decision->covered.position_m, 1.0, 1e-9);
}

TEST(HypothesisSet, APoseThatCoversTheImageNoBetterThanNoneIsNeverTaken) {
  Robot robot;
  for (int frame = 0; frame < 10; ++frame) {
    EXPECT_FALSE(robot.see(movedOn(0.6 * frame, HypothesisSetOptions{}.none_score - 1.0)));
  }
}

TEST(HypothesisSet, ViewsThatNoOnePoseMovedByTheOdometryExplainsTakeNone) {
  Robot robot;
  // The robot's odometry says it drove 2 m, yet its camera sees the first view.
  const std::vector<Fit> fits = {{truthAfter(0.0), 15.0}};
  robot.see({0.0, fits, fits});
  for (int frame = 0; frame < 5; ++frame) {
    EXPECT_FALSE(robot.see({2.0, fits, fits})) << "frame " << frame;
  }
}

TEST(HypothesisSet, AHypothesisTooWideToTrackFromWaitsForASecondView) {
  Robot robot;
  const auto too_wide = [](const PoseWithCovariance&) { return false; };
  for (int frame = 0; frame < 5; ++frame) {
    EXPECT_FALSE(robot.see(movedOn(0.0, 25.0), too_wide));
  }
  expectAtTruth(robot.see(movedOn(0.6, 25.0), too_wide), 0.6);
}

TEST(HypothesisSet, AHypothesisFoundLateIsWeighedOnTheEarlierFramesToo) {
  Robot robot;
  // The first frame's grid proposes only the rival, though the truth fits.
  Frame first = standingBeforeTwoFits(15.0, 14.0, 1.6);
  first.proposed = {first.fits[1]};
  EXPECT_FALSE(robot.see(first));
  EXPECT_FALSE(robot.see(movedOn(0.6))) << "proposed by one search only";
  EXPECT_EQ(robot.rescoredFrames(), std::vector<uint64_t>{0});
  expectAtTruth(robot.see(movedOn(1.2)), 1.2);
}

TEST(HypothesisSet, APoseOnlyTheRobotsMotionCarriesIsTakenOnceItLedAFullWindowOfViews) {
  Robot robot;
  // Proposed once; later frames align it from where the motion carries it.
  robot.see(movedOn(0.0, 25.0));
  const int full_window = HypothesisSetOptions{}.max_views;
  for (int frame = 1; frame < full_window - 1; ++frame) {
    Frame carried_only = movedOn(0.6 * frame, 25.0);
    carried_only.proposed.clear();
    EXPECT_FALSE(robot.see(carried_only)) << "frame " << frame;
    EXPECT_NE(robot.undecided().find("nor led every view"), std::string::npos) << robot.undecided();
  }
  Frame last = movedOn(0.6 * (full_window - 1), 25.0);
  last.proposed.clear();
  expectAtTruth(robot.see(last), 0.6 * (full_window - 1));
}

TEST(HypothesisSet, APoseOnlyTheRobotsMotionCarriesIsNotTakenWhileAViewPreferredAnother) {
  Robot robot;
  robot.see(movedOn(0.0, 25.0));
  // The second view's grid finds another pose that covers that view better.
  Frame rival_view = movedOn(0.6, 25.0);
  rival_view.proposed = {{at(6.0, 20.6), 27.0}};
  robot.see(rival_view);
  const int full_window = HypothesisSetOptions{}.max_views;
  for (int frame = 2; frame <= full_window; ++frame) {
    Frame carried_only = movedOn(0.6 * frame, 25.0);
    carried_only.proposed.clear();
    EXPECT_FALSE(robot.see(carried_only))
        << "frame " << frame << ": the rival's view is in the window";
  }
  // Once the rival's view has left the window, the truth led every view in it.
  Frame later = movedOn(0.6 * (full_window + 1), 25.0);
  later.proposed.clear();
  expectAtTruth(robot.see(later), 0.6 * (full_window + 1));
}

TEST(HypothesisSet, TheLatestFrameMustAlignItBestOfAllWithEnoughInliers) {
  Robot outscored;
  outscored.see(standingBeforeTwoFits(25.0, 12.0, 1.6));
  Frame another_best = standingBeforeTwoFits(25.0, 12.0, 1.6);
  another_best.proposed.push_back({at(5.0, 30.0), 26.0});
  EXPECT_FALSE(outscored.see(another_best)) << "another pose scores best in it";

  Robot few_inliers;
  few_inliers.see(standingBeforeTwoFits(25.0, 12.0, 1.6));
  Frame weak = standingBeforeTwoFits(25.0, 12.0, 1.6);
  weak.proposed[0].inliers = weak.fits[0].inliers = kMinInliers - 1;
  EXPECT_FALSE(few_inliers.see(weak));
  expectAtTruth(few_inliers.see(standingBeforeTwoFits(25.0, 12.0, 1.6)), 0.0);
}

TEST(HypothesisSet, KeepsAWindowOfTheLastViews) {
  HypothesisSetOptions options;
  options.max_views = 3;
  Robot robot(options);
  for (int frame = 0; frame < 6; ++frame) {
    robot.see(movedOn(0.6 * frame));
  }
  robot.see(movedOn(3.2));  // 0.2 m on from the last view's keyframe: in that view
  EXPECT_EQ(robot.set().windowFrames(), (std::vector<uint64_t>{3, 4, 5}));
}

TEST(HypothesisSet, ANewOdometryChainStartsAfresh) {
  Robot robot;
  robot.see(standingBeforeTwoFits(15.0, 14.0, 1.6));
  robot.see(standingBeforeTwoFits(15.0, 14.0, 1.6));
  OdometryPose restarted;
  restarted.epoch = 1;
  EXPECT_TRUE(robot.set().carriedStarts(restarted).empty());
  Frame after_restart = movedOn(0.0, 25.0);
  after_restart.epoch = 1;
  EXPECT_FALSE(robot.see(after_restart)) << "one frame of the new chain";
  EXPECT_EQ(robot.set().size(), 1u);
  EXPECT_EQ(robot.set().windowFrames().size(), 1u);
}

TEST(PoseOffset, IsTheDistanceAndTheRotationAngleBetweenTwoPoses) {
  Eigen::Isometry3d turned = at(3.0, 4.0);
  turned.linear() = Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const PoseOffset offset = PoseOffset::between(at(0.0, 0.0), turned);
  EXPECT_NEAR(offset.position_m, 5.0, 1e-12);
  EXPECT_NEAR(offset.rotation_rad, 0.2, 1e-12);
  EXPECT_TRUE(offset.within({5.0, 0.2 + 1e-9}));
  EXPECT_FALSE(offset.within({4.9, 1.0}));
  const PoseOffset farthest = offset.farthest({1.0, 0.5});
  EXPECT_EQ(farthest.position_m, 5.0);
  EXPECT_EQ(farthest.rotation_rad, 0.5);
}

}  // namespace
}  // namespace lineloc
