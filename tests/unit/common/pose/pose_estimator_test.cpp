// Noise-free recovery, statuses and stop conditions of estimatePose.
#include "common/pose/pose_estimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/unit/common/pose/pose_test_scene.h"

namespace lineloc {
namespace {

using test::makeScene;
using test::rotationErrorRad;
using test::SceneOptions;
using test::translationErrorM;

// Noise-free data: refinement stops at the floating-point floor. Pixel
// coordinates ~1e2-1e3 carry ~1e-13 px rounding, i.e. 1e-16 rad at f = 800 px
// and 1e-15 m at 10 m; 1e-9 leaves six orders of margin yet catches any bias.
constexpr double kNoiseFreeTolerance = 1e-9;

struct NoiseFreeCase {
  const char* name;
  SceneOptions scene;
  bool needs_prior;
};

class NoiseFreeTest : public ::testing::TestWithParam<NoiseFreeCase> {};

TEST_P(NoiseFreeTest, RecoversThePoseTo1e9) {
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    SceneOptions scene_options = GetParam().scene;
    scene_options.seed = seed;
    const test::Scene scene = makeScene(scene_options);
    PoseOptions options;
    if (GetParam().needs_prior) {
      std::mt19937 random(seed);
      options.prior_T_world_camera = test::perturbPose(scene.T_world_camera, 0.05, 0.3, random);
    }
    const PoseEstimate estimate = estimatePose(scene.problem, options);
    ASSERT_EQ(estimate.status, PoseStatus::kConverged) << estimate.message << " seed " << seed;
    EXPECT_LT(rotationErrorRad(estimate.T_world_camera.pose, scene.T_world_camera),
              kNoiseFreeTolerance);
    EXPECT_LT(translationErrorM(estimate.T_world_camera.pose, scene.T_world_camera),
              kNoiseFreeTolerance);
    EXPECT_LT(estimate.rms_residual_px, 1e-9);
    EXPECT_EQ(estimate.point_residuals.size(), scene.problem.points.size());
    EXPECT_EQ(estimate.line_residuals.size(), scene.problem.lines.size());
  }
}

INSTANTIATE_TEST_SUITE_P(Configurations, NoiseFreeTest,
                         ::testing::Values(NoiseFreeCase{"planar4", {4, 0, true}, false},
                                           NoiseFreeCase{"planar30", {30, 0, true}, false},
                                           NoiseFreeCase{"points6", {6, 0, false}, false},
                                           NoiseFreeCase{"points100", {100, 0, false}, false},
                                           NoiseFreeCase{"lines3", {0, 3, false}, true},
                                           NoiseFreeCase{"lines6", {0, 6, false}, false},
                                           NoiseFreeCase{"lines100", {0, 100, false}, false},
                                           NoiseFreeCase{"planar4_lines3", {4, 3, true}, false},
                                           NoiseFreeCase{"points2_lines1", {2, 1, false}, true},
                                           NoiseFreeCase{
                                               "points20_lines50", {20, 50, false}, false}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(PoseEstimatorTest, FewerThanSixConstraintsAreNotEnough) {
  const test::Scene scene = makeScene({2, 0, false, 0.0, 3});
  EXPECT_EQ(estimatePose(scene.problem).status, PoseStatus::kNotEnoughCorrespondences);
}

TEST(PoseEstimatorTest, FourNonCoplanarPointsNeedAPrior) {
  const test::Scene scene = makeScene({4, 0, false, 0.0, 3});
  const PoseEstimate estimate = estimatePose(scene.problem);
  EXPECT_EQ(estimate.status, PoseStatus::kNotEnoughCorrespondences);
  EXPECT_NE(estimate.message.find("prior"), std::string::npos) << estimate.message;
}

TEST(PoseEstimatorTest, CollinearPointsAreDegenerate) {
  test::Scene scene = makeScene({8, 0, false, 0.0, 4});
  const Eigen::Isometry3d T_camera_world = scene.T_world_camera.inverse();
  for (size_t i = 0; i < scene.problem.points.size(); ++i) {
    auto& point = scene.problem.points[i];
    point.p_world = Eigen::Vector3d(0.1 * static_cast<double>(i), 0.05, -0.2);
    point.pixel = scene.problem.camera.project(T_camera_world * point.p_world);
  }
  const PoseEstimate estimate = estimatePose(scene.problem);
  EXPECT_EQ(estimate.status, PoseStatus::kDegenerate);
  EXPECT_NE(estimate.message.find("collinear"), std::string::npos) << estimate.message;
}

// Lines from `count` directions through one point, or all along one direction.
PoseProblem lineBundle(bool concurrent) {
  const test::Scene scene = makeScene({0, 8, false, 0.0, 5});
  PoseProblem problem = scene.problem;
  const Eigen::Isometry3d T_camera_world = scene.T_world_camera.inverse();
  const Eigen::Vector3d apex(0.2, -0.1, 0.3);
  for (auto& line : problem.lines) {
    const Eigen::Vector3d direction = (line.end_world - line.start_world).normalized();
    line.start_world = concurrent ? apex : line.start_world;
    line.end_world =
        concurrent ? apex + direction : line.start_world + Eigen::Vector3d(0.0, 0.0, 1.0);
    line.start_pixel = problem.camera.project(T_camera_world * line.start_world);
    line.end_pixel = problem.camera.project(T_camera_world * line.end_world);
  }
  return problem;
}

TEST(PoseEstimatorTest, ParallelLinesAreDegenerate) {
  const PoseEstimate estimate = estimatePose(lineBundle(false));
  EXPECT_EQ(estimate.status, PoseStatus::kDegenerate);
  EXPECT_NE(estimate.message.find("parallel"), std::string::npos) << estimate.message;
}

TEST(PoseEstimatorTest, ConcurrentLinesAreDegenerate) {
  const PoseEstimate estimate = estimatePose(lineBundle(true));
  EXPECT_EQ(estimate.status, PoseStatus::kDegenerate);
  EXPECT_NE(estimate.message.find("one point"), std::string::npos) << estimate.message;
}

TEST(PoseEstimatorTest, NonFiniteInputIsNamed) {
  test::Scene scene = makeScene({10, 2, false, 0.0, 6});
  scene.problem.points[3].pixel.y() = std::numeric_limits<double>::quiet_NaN();
  const PoseEstimate estimate = estimatePose(scene.problem);
  EXPECT_EQ(estimate.status, PoseStatus::kInvalidInput);
  EXPECT_NE(estimate.message.find("point 3: pixel"), std::string::npos) << estimate.message;
}

TEST(PoseEstimatorTest, InvalidCovarianceAndSegmentsAreNamed) {
  const test::Scene scene = makeScene({10, 3, false, 0.0, 7});
  PoseProblem problem = scene.problem;
  problem.lines[2].end_covariance << 1.0, 2.0, 2.0, 1.0;
  EXPECT_NE(estimatePose(problem).message.find("line 2: end covariance"), std::string::npos);
  problem = scene.problem;
  problem.lines[1].end_pixel = problem.lines[1].start_pixel;
  EXPECT_NE(estimatePose(problem).message.find("line 1: image segment"), std::string::npos);
  problem = scene.problem;
  problem.points[0].p_world.x() = 1e12;
  EXPECT_EQ(estimatePose(problem).status, PoseStatus::kInvalidInput);
  problem = scene.problem;
  problem.camera.fx = -1.0;
  EXPECT_NE(estimatePose(problem).message.find("camera"), std::string::npos);
}

TEST(PoseEstimatorTest, PriorSeeingPointsBehindTheCameraIsRejected) {
  const test::Scene scene = makeScene({10, 0, false, 0.0, 8});
  PoseOptions options;
  Eigen::Isometry3d turned_around = scene.T_world_camera;
  turned_around.linear() = scene.T_world_camera.linear() *
                           Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()).toRotationMatrix();
  options.prior_T_world_camera = turned_around;
  EXPECT_EQ(estimatePose(scene.problem, options).status, PoseStatus::kBehindCamera);
}

TEST(PoseEstimatorTest, IterationLimitIsReported) {
  const test::Scene scene = makeScene({20, 0, false, 1.0, 9});
  std::mt19937 random(9);
  PoseOptions options;
  options.prior_T_world_camera = test::perturbPose(scene.T_world_camera, 0.2, 0.5, random);
  options.refinement.max_iterations = 1;
  const PoseEstimate estimate = estimatePose(scene.problem, options);
  EXPECT_EQ(estimate.status, PoseStatus::kIterationLimit);
  EXPECT_EQ(estimate.iterations, 1);
}

// Stopping once a step is a thousandth of a standard deviation long ends
// where the tight tolerances end, to far below the estimate's own uncertainty:
// (x - x_tight)^T I (x - x_tight) stays near (1e-3)^2.
TEST(PoseEstimatorTest, StepsBelowTheUncertaintyStopTheRefinement) {
  const test::Scene scene = makeScene({10, 15, false, 1.0, 12});
  std::mt19937 random(12);
  PoseOptions tight;
  tight.prior_T_world_camera = test::perturbPose(scene.T_world_camera, 0.05, 0.3, random);
  tight.refinement.loss = RobustLoss::kCauchy;
  PoseOptions loose = tight;
  loose.refinement.step_information_tolerance = 1e-6;
  const PoseEstimate reference = estimatePose(scene.problem, tight);
  const PoseEstimate estimate = estimatePose(scene.problem, loose);
  ASSERT_TRUE(reference.ok()) << reference.message;
  ASSERT_TRUE(estimate.ok()) << estimate.message;
  EXPECT_LT(estimate.iterations, reference.iterations);
  const Eigen::Matrix<double, 6, 1> difference =
      test::poseError(reference.T_world_camera.pose, estimate.T_world_camera.pose);
  const double squared_sigmas =
      difference.dot(reference.T_world_camera.covariance.ldlt().solve(difference));
  EXPECT_LT(squared_sigmas, 1e-4);
}

TEST(PoseEstimatorTest, WrongMatchesAreInconsistent) {
  test::Scene scene = makeScene({20, 0, false, 0.5, 10});
  for (size_t i = 0; i + 1 < scene.problem.points.size(); i += 2) {
    std::swap(scene.problem.points[i].pixel, scene.problem.points[i + 1].pixel);
  }
  PoseOptions options;
  options.prior_T_world_camera = scene.T_world_camera;
  EXPECT_EQ(estimatePose(scene.problem, options).status, PoseStatus::kInconsistent);
}

// A small plane far away, seen nearly head-on, with 1 px noise: the mirrored
// pose fits almost as well (Schweighofer & Pinz 2006), so both are reported.
TEST(PoseEstimatorTest, PlanarFlipIsAmbiguous) {
  PoseProblem problem;
  problem.camera = test::testCamera();
  Eigen::Isometry3d T_camera_world = Eigen::Isometry3d::Identity();
  T_camera_world.linear() = Eigen::AngleAxisd(0.15, Eigen::Vector3d::UnitX()).toRotationMatrix();
  T_camera_world.translation() = Eigen::Vector3d(0.0, 0.0, 30.0);
  std::mt19937 random(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (const auto& [x, y] : {std::pair{-0.2, -0.2}, {0.2, -0.2}, {0.2, 0.2}, {-0.2, 0.2}}) {
    const Eigen::Vector3d p_world(x, y, 0.0);
    const Eigen::Vector2d pixel = problem.camera.project(T_camera_world * p_world);
    problem.points.push_back({p_world, pixel + Eigen::Vector2d(noise(random), noise(random)),
                              Eigen::Matrix2d::Identity()});
  }
  const PoseEstimate estimate = estimatePose(problem);
  EXPECT_EQ(estimate.status, PoseStatus::kAmbiguous) << estimate.message;
  ASSERT_TRUE(estimate.alternative_T_world_camera.has_value());
  EXPECT_GT(rotationErrorRad(*estimate.alternative_T_world_camera, estimate.T_world_camera.pose),
            0.05);
  EXPECT_LT(estimate.alternative_rms_residual_px, 3.0);
}

TEST(PoseEstimatorTest, StatusNamesAreDistinct) {
  EXPECT_STREQ(toString(PoseStatus::kConverged), "converged");
  EXPECT_STREQ(toString(PoseStatus::kAmbiguous), "ambiguous");
  EXPECT_STRNE(toString(PoseStatus::kDegenerate), toString(PoseStatus::kDiverged));
}

}  // namespace
}  // namespace lineloc
