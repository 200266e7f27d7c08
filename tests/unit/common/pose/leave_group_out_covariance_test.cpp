// The jackknife covariance of a refined pose: it agrees with the propagated
// noise on clean data, covers the error a few consistently biased lines cause
// where the propagated noise does not, and is infinite when one group alone
// carries part of the pose.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include "common/pose/pose_refinement.h"
#include "tests/unit/common/pose/pose_test_scene.h"

namespace lineloc {
namespace {

using test::kChi2Six9973;
using test::makeScene;
using test::normalizedErrorSquared;
using test::poseError;
using test::Scene;
using test::SceneOptions;

constexpr double kStatedVariancePx2 = 1.5 * 1.5;

// The refinement as the backbone's alignment runs it: Cauchy loss, stopped
// at a thousandth of a standard deviation.
RefinementOptions robustOptions() {
  RefinementOptions options;
  options.loss = RobustLoss::kCauchy;
  options.step_information_tolerance = 1e-6;
  return options;
}

std::vector<int> ownGroups(const PoseProblem& problem) {
  std::vector<int> groups(problem.lines.size());
  std::iota(groups.begin(), groups.end(), 0);
  return groups;
}

// One scene measured again and again with fresh noise: the jackknife,
// averaged over the draws, matches the estimate's actual scatter, whitened:
// tr(C^-1 mean(Sigma_J)) / 6 near 1, with C the empirical covariance of the
// estimates. For least squares the delete-one jackknife overestimates by
// about 1 / (1 - h), h = 6 / 40 the mean leverage of a line: 1.18. Around
// that, C scatters by sqrt(2 / 200) = 10 % (one jackknife by sqrt(2 / 40) =
// 22 %, their mean over 200 draws by 1.6 %): three standard deviations give
// 0.85 to 1.5.
TEST(LeaveGroupOutCovariance, MatchesTheScatterOfTheEstimate) {
  constexpr int kDraws = 200;
  constexpr double kNoisePx = 0.5;
  const Scene clean = makeScene({.lines = 40, .seed = 11});
  std::mt19937 random(5);
  std::normal_distribution<double> noise(0.0, kNoisePx);
  const Eigen::Matrix2d covariance = kNoisePx * kNoisePx * Eigen::Matrix2d::Identity();
  std::vector<Eigen::Matrix<double, 6, 1>> errors;
  Matrix6d jackknife_sum = Matrix6d::Zero();
  for (int draw = 0; draw < kDraws; ++draw) {
    PoseProblem problem = clean.problem;
    for (LineCorrespondence& line : problem.lines) {
      line.start_pixel += Eigen::Vector2d(noise(random), noise(random));
      line.end_pixel += Eigen::Vector2d(noise(random), noise(random));
      line.start_covariance = covariance;
      line.end_covariance = covariance;
    }
    const PoseEstimate estimate = refinePose(problem, clean.T_world_camera);
    ASSERT_TRUE(estimate.ok()) << estimate.message;
    const Eigen::Isometry3d& pose = estimate.T_world_camera.pose;
    jackknife_sum += leaveGroupOutCovariance(problem, pose, ownGroups(problem), {});
    errors.push_back(poseError(pose, clean.T_world_camera));
  }
  Matrix6d scatter = Matrix6d::Zero();
  for (const auto& error : errors) {
    scatter += error * error.transpose();
  }
  scatter /= kDraws;
  const double ratio = scatter.ldlt().solve(jackknife_sum / kDraws).trace() / 6.0;
  EXPECT_GT(ratio, 0.85);
  EXPECT_LT(ratio, 1.5);
}

// Each line is stated to 1.5 px (the model's survey error seen from 10 m)
// and measured to 0.3 px. Five of twenty lines then measured 3 px to the
// right (window edges beside a building edge): each within two stated sigma,
// so none is an outlier, and together they pull the pose. The jackknife
// follows what the residuals show: small against the stated noise on the
// clean scene, several times larger once the five disagree with the rest.
TEST(LeaveGroupOutCovariance, LinesBiasedTheSameWayWidenIt) {
  constexpr int kScenes = 20;
  const RefinementOptions options = robustOptions();
  // tr(Sigma^-1 Sigma_J) / 6 of the scene's estimate.
  const auto whitenedJackknife = [&](const PoseProblem& problem, const Eigen::Isometry3d& truth) {
    const PoseEstimate estimate = refinePose(problem, truth, options);
    EXPECT_TRUE(estimate.ok()) << estimate.message;
    const Matrix6d jackknife =
        leaveGroupOutCovariance(problem, estimate.T_world_camera.pose, ownGroups(problem), options);
    return estimate.T_world_camera.covariance.ldlt().solve(jackknife).trace() / 6.0;
  };
  for (int trial = 0; trial < kScenes; ++trial) {
    Scene scene =
        makeScene({.lines = 20, .noise_px = 0.3, .seed = static_cast<uint32_t>(100 + trial)});
    for (LineCorrespondence& line : scene.problem.lines) {
      line.start_covariance = line.end_covariance =
          kStatedVariancePx2 * Eigen::Matrix2d::Identity();
    }
    const double clean = whitenedJackknife(scene.problem, scene.T_world_camera);
    for (size_t i = 0; i < 5; ++i) {
      scene.problem.lines[i].start_pixel.x() += 3.0;
      scene.problem.lines[i].end_pixel.x() += 3.0;
    }
    const double biased = whitenedJackknife(scene.problem, scene.T_world_camera);
    EXPECT_LT(clean, 0.5) << "scene " << trial;
    EXPECT_GT(biased, 2.0 * clean) << "scene " << trial;
  }
}

// The image pieces of one line share its error: grouped, they are left out
// together, and the jackknife sees the bias that three pieces of one biased
// line cause; taken one by one, the other two pieces hide it.
TEST(LeaveGroupOutCovariance, PiecesOfOneLineAreLeftOutTogether) {
  Scene scene = makeScene({.lines = 20, .noise_px = 0.3, .seed = 7});
  LineCorrespondence biased = scene.problem.lines.front();
  biased.start_pixel.x() += 3.0;
  biased.end_pixel.x() += 3.0;
  scene.problem.lines.front() = biased;
  std::vector<int> grouped = ownGroups(scene.problem);
  for (int piece = 0; piece < 2; ++piece) {
    scene.problem.lines.push_back(biased);
    grouped.push_back(0);
  }
  const std::vector<int> one_by_one = ownGroups(scene.problem);
  const RefinementOptions options = robustOptions();
  const PoseEstimate estimate = refinePose(scene.problem, scene.T_world_camera, options);
  ASSERT_TRUE(estimate.ok()) << estimate.message;
  const Eigen::Isometry3d& pose = estimate.T_world_camera.pose;
  const double nees_grouped = normalizedErrorSquared(
      {pose, leaveGroupOutCovariance(scene.problem, pose, grouped, options)}, scene.T_world_camera);
  const double nees_one_by_one = normalizedErrorSquared(
      {pose, leaveGroupOutCovariance(scene.problem, pose, one_by_one, options)},
      scene.T_world_camera);
  EXPECT_LT(nees_grouped, nees_one_by_one);
  EXPECT_LE(nees_grouped, kChi2Six9973);
}

// Three lines give exactly six equations: without any one of them the pose is
// undetermined, and so is its jackknife.
TEST(LeaveGroupOutCovariance, IsInfiniteWhenOneGroupCarriesPartOfThePose) {
  const Scene scene = makeScene({.lines = 3, .noise_px = 0.0, .seed = 3});
  const Matrix6d jackknife =
      leaveGroupOutCovariance(scene.problem, scene.T_world_camera, ownGroups(scene.problem), {});
  EXPECT_FALSE(jackknife.allFinite());
  const Scene enough = makeScene({.lines = 12, .noise_px = 0.0, .seed = 3});
  EXPECT_TRUE(
      leaveGroupOutCovariance(enough.problem, enough.T_world_camera, ownGroups(enough.problem), {})
          .allFinite());
}

// One group per line, each naming a line index: anything else is a caller's
// bug, named rather than read out of bounds.
TEST(LeaveGroupOutCovariance, GroupsNotOnePerLineAreRejected) {
  const Scene scene = makeScene({.lines = 6, .noise_px = 0.0, .seed = 3});
  const std::vector<int> too_few = {0, 1, 2};
  const std::vector<int> out_of_range = {0, 1, 2, 3, 4, 6};
  EXPECT_THROW(leaveGroupOutCovariance(scene.problem, scene.T_world_camera, too_few, {}),
               std::invalid_argument);
  EXPECT_THROW(leaveGroupOutCovariance(scene.problem, scene.T_world_camera, out_of_range, {}),
               std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
