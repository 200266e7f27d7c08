#include <fmt/format.h>
#include <gtest/gtest.h>

#include "sim/eval/fix_consistency.h"

namespace lineloc {
namespace {

// Ground truth along x at 1 m/s for 10 s, every 0.1 s.
std::vector<StampedPose> straightDrive() {
  std::vector<StampedPose> truth;
  for (int64_t i = 0; i <= 100; ++i) {
    StampedPose pose;
    pose.stamp_ns = i * 100'000'000;
    pose.pose.translation() = Eigen::Vector3d(0.1 * static_cast<double>(i), 0.0, 1.5);
    truth.push_back(pose);
  }
  return truth;
}

// A fix at `stamp_ns` (between ground-truth samples), `sigmas` standard
// deviations (2 cm) off in y.
LoggedFix fixOff(int64_t stamp_ns, double sigmas, const std::string& status = "ok") {
  LoggedFix fix;
  fix.stamp_ns = stamp_ns;
  fix.status = status;
  fix.latency_ms = 4.5;
  fix.T_world_camera.covariance = diagonalPoseCovariance(0.02, 0.001);
  fix.T_world_camera.pose.translation() =
      Eigen::Vector3d(1e-9 * static_cast<double>(stamp_ns), 0.02 * sigmas, 1.5);
  return fix;
}

TEST(FixConsistency, CountsOkFixesBeyondThreeSigmaAgainstInterpolatedTruth) {
  const std::vector<LoggedFix> fixes = {
      fixOff(1'050'000'000, 0.0, "no_match_computed"),  // no pose yet
      fixOff(2'050'000'000, 2.0),                       // NEES 4
      fixOff(3'050'000'000, 5.0),                       // NEES 25: precise and wrong
      fixOff(4'050'000'000, 50.0, "too_few_matches"),   // not an answer with a pose
      fixOff(20'000'000'000, 0.0),                      // after the ground truth ends
  };
  const FixConsistencyOptions options;
  const FixConsistency consistency = evaluateFixConsistency(straightDrive(), fixes, options);
  EXPECT_EQ(consistency.answers, 5);
  EXPECT_EQ(consistency.ok, 3);
  ASSERT_EQ(consistency.tally.nees.size(), 2u);
  EXPECT_NEAR(consistency.tally.nees[0], 4.0, 1e-6);
  EXPECT_NEAR(consistency.tally.nees[1], 25.0, 1e-6);
  ASSERT_EQ(consistency.tally.beyond_bound.size(), 1u);
  const BeyondBound& wrong = consistency.tally.beyond_bound.front();
  EXPECT_NEAR(wrong.time_s, 3.05, 1e-9);
  EXPECT_NEAR(wrong.nees, 25.0, 1e-6);
  EXPECT_NEAR(wrong.position_error_m, 0.1, 1e-9);
  EXPECT_NEAR(wrong.sigma_along_error_m, 0.02, 1e-9);
  EXPECT_EQ(consistency.first_ok_received_ns, 2'050'000'000 + 4'500'000);
  // The frames from the first OK one on: 3 of 4 OK.
  EXPECT_EQ(consistency.answers_from_first_ok, 4);
  const std::string line = formatFixConsistency(consistency, options);
  EXPECT_NE(line.find("fixes: 5 answers, 3 ok (75.0 % of the 4 from the first on); "),
            std::string::npos)
      << line;
  EXPECT_NE(line.find("1 beyond chi2_6(0.9973) = 20.06"), std::string::npos) << line;
  EXPECT_NE(line.find("\n  beyond at 3.050 s: NEES 25.0, 0.100 m off, sigma 0.020 m along it\n"),
            std::string::npos)
      << line;
}

// Of many fixes beyond the bound, the worst kListedBeyondBound are listed, in
// the order they came.
TEST(FixConsistency, ListsTheWorstFixesBeyondTheBoundInTimeOrder) {
  std::vector<LoggedFix> fixes;
  for (int64_t i = 1; i <= 8; ++i) {
    // 4 + i sigmas off at i s: the last five are the worst.
    fixes.push_back(fixOff(i * 1'000'000'000 + 50'000'000, 4.0 + static_cast<double>(i)));
  }
  const std::string line =
      formatFixConsistency(evaluateFixConsistency(straightDrive(), fixes, {}), {});
  EXPECT_NE(line.find("8 beyond chi2_6(0.9973)"), std::string::npos) << line;
  size_t at = 0;
  for (int i = 8 - kListedBeyondBound + 1; i <= 8; ++i) {
    const size_t found =
        line.find(fmt::format("  beyond at {}.050 s: NEES {:.1f}", i, (4.0 + i) * (4.0 + i)));
    ASSERT_NE(found, std::string::npos) << line;
    EXPECT_GT(found, at) << line;
    at = found;
  }
  EXPECT_EQ(line.find("beyond at 3.050 s"), std::string::npos) << line;
}

TEST(FixConsistency, SaysSoWhenNoFixHasGroundTruth) {
  const FixConsistency consistency =
      evaluateFixConsistency(straightDrive(), {fixOff(20'000'000'000, 0.0)}, {});
  EXPECT_TRUE(consistency.tally.nees.empty());
  EXPECT_EQ(formatFixConsistency(consistency, {}),
            "fixes: 1 answers, 1 ok (100.0 % of the 1 from the first on), none with ground "
            "truth\n");
  EXPECT_EQ(consistency.first_ok_received_ns, 20'004'500'000);
}

TEST(FixConsistency, WithoutAnOkFixNoAnswerCountsFromTheFirst) {
  const FixConsistency consistency =
      evaluateFixConsistency(straightDrive(), {fixOff(1'050'000'000, 0.0, "ambiguous")}, {});
  EXPECT_EQ(consistency.answers_from_first_ok, 0);
  EXPECT_FALSE(consistency.first_ok_received_ns);
  EXPECT_EQ(formatFixConsistency(consistency, {}),
            "fixes: 1 answers, 0 ok, none with ground truth\n");
}

// The robot's reported states from the first OK fix on: each one's NEES
// against the interpolated truth, the ones beyond the bound counted.
TEST(StateConsistency, CountsStatesBeyondThreeSigmaFromTheFirstFix) {
  const auto stateOff = [](int64_t stamp_ns, double sigmas) {
    const LoggedFix fix = fixOff(stamp_ns, sigmas);
    return StampedPoseWithCovariance{fix.stamp_ns, fix.T_world_camera};
  };
  const std::vector<StampedPoseWithCovariance> states = {
      stateOff(1'000'000'000, 50.0),  // before the first fix: from DGPS alone
      stateOff(2'050'000'000, 1.0),   // NEES 1
      stateOff(3'050'000'000, 6.0),   // NEES 36: the robot sure of a wrong pose
      stateOff(20'000'000'000, 0.0),  // after the ground truth ends
  };
  const FixConsistencyOptions options;
  const StateConsistency consistency =
      evaluateStateConsistency(straightDrive(), states, 2'000'000'000, options);
  EXPECT_EQ(consistency.states, 3);
  ASSERT_EQ(consistency.tally.nees.size(), 2u);
  EXPECT_NEAR(consistency.tally.nees[0], 1.0, 1e-6);
  EXPECT_NEAR(consistency.tally.nees[1], 36.0, 1e-6);
  ASSERT_EQ(consistency.tally.beyond_bound.size(), 1u);
  EXPECT_NEAR(consistency.tally.beyond_bound.front().nees, 36.0, 1e-6);
  const std::string line = formatStateConsistency(consistency, options);
  EXPECT_NE(line.find("robot states: 3 from the first OK fix on; "), std::string::npos) << line;
  EXPECT_NE(line.find("1 beyond chi2_6(0.9973) = 20.06"), std::string::npos) << line;
  EXPECT_EQ(
      formatStateConsistency(
          evaluateStateConsistency(straightDrive(), states, 10'000'000'000, options), options),
      "robot states: 1, none with ground truth\n");
}

}  // namespace
}  // namespace lineloc
