// Randomly generated degenerate or hostile inputs: no crash, no hang, and
// never kConverged with a wrong pose. Each input starts from a noise-free
// scene with a known true pose and is damaged one way; where the damaged data
// are still exactly consistent with the true pose (degenerate sets, lines
// through the camera centre), a converged pose must be that pose.
//
// The count is LINELOC_POSE_HOSTILE_INPUTS (default 20000, a few seconds);
// the CTest test pose_hostile_inputs_million (label "long") runs 1,000,000.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <vector>

#include "common/pose/pose_estimator.h"
#include "tests/unit/common/pose/pose_test_scene.h"

namespace lineloc {
namespace {

enum class Damage {
  kNonFinite,
  kHugeNumber,
  kCoincidentPoints,
  kCollinearPoints,
  kParallelLines,
  kConcurrentLines,
  kLinesThroughCameraCentre,
  kPointsBehindCamera,
  kGarbage,
  kCount,
};

int hostileInputCount() {
  const char* value = std::getenv("LINELOC_POSE_HOSTILE_INPUTS");
  return value ? std::atoi(value) : 20000;
}

std::vector<double*> numbersOf(PoseProblem& problem) {
  std::vector<double*> numbers = {&problem.camera.fx, &problem.camera.fy, &problem.camera.cx,
                                  &problem.camera.cy, &problem.camera.skew};
  const auto add = [&](auto& matrix) {
    for (Eigen::Index i = 0; i < matrix.size(); ++i)
      numbers.push_back(matrix.data() + i);
  };
  for (auto& point : problem.points) {
    add(point.p_world);
    add(point.pixel);
    add(point.covariance);
  }
  for (auto& line : problem.lines) {
    add(line.start_world);
    add(line.end_world);
    add(line.start_pixel);
    add(line.end_pixel);
    add(line.start_covariance);
    add(line.end_covariance);
  }
  return numbers;
}

class HostileInputGenerator {
 public:
  explicit HostileInputGenerator(uint32_t seed) : random_(seed) {}

  Damage damage() const { return damage_; }
  const test::Scene& scene() const { return scene_; }

  void generate(int index) {
    damage_ = static_cast<Damage>(index % static_cast<int>(Damage::kCount));
    const int points = uniformInt(0, 10);
    const int lines = uniformInt(points == 0 ? 1 : 0, 6);
    scene_ = test::makeScene(
        {points, lines, uniformInt(0, 1) == 1, 0.0, static_cast<uint32_t>(random_())});
    centre_ = scene_.T_world_camera.translation();
    T_camera_world_ = scene_.T_world_camera.inverse();
    apply();
  }

 private:
  int uniformInt(int low, int high) {
    return std::uniform_int_distribution<int>(low, high)(random_);
  }
  bool coin() { return uniformInt(0, 2) == 0; }
  double uniform(double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(random_);
  }
  Eigen::Vector3d randomPoint() { return {uniform(-2, 2), uniform(-2, 2), uniform(-2, 2)}; }
  Eigen::Vector2d project(const Eigen::Vector3d& p_world) const {
    return scene_.problem.camera.project(T_camera_world_ * p_world);
  }

  void apply() {
    PoseProblem& problem = scene_.problem;
    switch (damage_) {
      case Damage::kNonFinite: {
        const std::vector<double*> numbers = numbersOf(problem);
        const double values[] = {std::numeric_limits<double>::quiet_NaN(),
                                 std::numeric_limits<double>::infinity(),
                                 -std::numeric_limits<double>::infinity()};
        *numbers[random_() % numbers.size()] = values[random_() % 3];
        break;
      }
      case Damage::kHugeNumber: {
        const std::vector<double*> numbers = numbersOf(problem);
        // Beyond every accepted range: 1e8 for coordinates, 1e12 px^2 for variances.
        const double huge = std::pow(10.0, uniform(12.5, 308.0));
        *numbers[random_() % numbers.size()] = uniformInt(0, 1) ? huge : -huge;
        break;
      }
      case Damage::kCoincidentPoints:
      case Damage::kCollinearPoints: {
        const Eigen::Vector3d origin = randomPoint();
        const Eigen::Vector3d direction = randomPoint().normalized();
        const double spacing = damage_ == Damage::kCoincidentPoints ? 0.0 : 0.1;
        problem.lines.clear();
        problem.points.resize(static_cast<size_t>(uniformInt(3, 12)));
        for (size_t i = 0; i < problem.points.size(); ++i) {
          problem.points[i].p_world = origin + spacing * static_cast<double>(i) * direction;
          problem.points[i].pixel = project(problem.points[i].p_world);
          problem.points[i].covariance = 0.01 * Eigen::Matrix2d::Identity();
        }
        break;
      }
      case Damage::kParallelLines:
      case Damage::kConcurrentLines: {
        const Eigen::Vector3d apex = randomPoint();
        const Eigen::Vector3d direction = randomPoint().normalized();
        problem.points.clear();
        problem.lines.resize(static_cast<size_t>(uniformInt(3, 8)));
        for (auto& line : problem.lines) {
          const bool parallel = damage_ == Damage::kParallelLines;
          line.start_world = parallel ? randomPoint() : apex;
          line.end_world = line.start_world + (parallel ? direction : randomPoint().normalized());
          line.start_pixel = project(line.start_world);
          line.end_pixel = project(line.end_world);
          line.start_covariance = line.end_covariance = 0.01 * Eigen::Matrix2d::Identity();
        }
        break;
      }
      case Damage::kLinesThroughCameraCentre:
        for (int k = uniformInt(1, 3); k > 0; --k) {
          const Eigen::Vector3d sight = (randomPoint() * 0.2 - centre_).normalized();
          LineCorrespondence line;
          line.start_world = centre_ + uniform(2.0, 5.0) * sight;
          line.end_world = line.start_world + uniform(0.5, 3.0) * sight;
          const Eigen::Vector2d pixel = project(line.start_world);
          const double angle = uniform(0.0, M_PI);
          line.start_pixel = pixel - 10.0 * Eigen::Vector2d(std::cos(angle), std::sin(angle));
          line.end_pixel = pixel + 10.0 * Eigen::Vector2d(std::cos(angle), std::sin(angle));
          line.start_covariance = line.end_covariance = 0.01 * Eigen::Matrix2d::Identity();
          problem.lines.push_back(line);
        }
        break;
      case Damage::kPointsBehindCamera:
        // Mirrored through the camera centre, a point keeps its pixel. The
        // first feature is mirrored; the last point and the last line are kept
        // (a whole mirrored set is explained exactly by the camera turned
        // around); others at random.
        for (size_t i = 0; i + 1 < problem.points.size(); ++i) {
          if (i == 0 || coin()) {
            problem.points[i].p_world = 2.0 * centre_ - problem.points[i].p_world;
          }
        }
        for (size_t i = 0; i + 1 < problem.lines.size(); ++i) {
          if ((i == 0 && problem.points.size() < 2) || coin()) {
            problem.lines[i].end_world = 2.0 * centre_ - problem.lines[i].end_world;
          }
        }
        break;
      case Damage::kGarbage:
        for (double* number : numbersOf(problem)) {
          if (uniformInt(0, 3) == 0) {
            *number = uniform(-1.0, 1.0) * std::pow(10.0, uniform(-12.0, 9.0));
          }
        }
        break;
      case Damage::kCount:
        break;
    }
  }

  std::mt19937 random_;
  Damage damage_ = Damage::kGarbage;
  test::Scene scene_;
  Eigen::Vector3d centre_;
  Eigen::Isometry3d T_camera_world_;
};

bool isConsistentWithTruth(Damage damage) {
  return damage == Damage::kCoincidentPoints || damage == Damage::kCollinearPoints ||
         damage == Damage::kParallelLines || damage == Damage::kConcurrentLines ||
         damage == Damage::kLinesThroughCameraCentre;
}

TEST(HostileInputTest, NoCrashNoHangNoWrongConvergedPose) {
  const int count = hostileInputCount();
  HostileInputGenerator generator(20261122u);
  std::vector<int> converged(static_cast<int>(Damage::kCount), 0);
  for (int index = 0; index < count; ++index) {
    generator.generate(index);
    const Damage damage = generator.damage();
    const test::Scene& scene = generator.scene();
    const PoseEstimate estimate = estimatePose(scene.problem);
    if (damage == Damage::kNonFinite || damage == Damage::kHugeNumber) {
      ASSERT_EQ(estimate.status, PoseStatus::kInvalidInput)
          << "input " << index << ": " << estimate.message;
    }
    if (!estimate.ok()) {
      ASSERT_FALSE(estimate.message.empty()) << "input " << index;
      continue;
    }
    ++converged[static_cast<int>(damage)];
    ASSERT_TRUE(isFinitePose(estimate.T_world_camera)) << "input " << index;
    ASSERT_TRUE(std::isfinite(estimate.rms_residual_px)) << "input " << index;
    ASSERT_GE(estimate.T_world_camera.covariance.diagonal().minCoeff(), 0.0) << "input " << index;
    ASSERT_NE(damage, Damage::kPointsBehindCamera)
        << "input " << index << ": converged although a feature is behind the camera";
    if (isConsistentWithTruth(damage)) {
      ASSERT_LT(test::rotationErrorRad(estimate.T_world_camera.pose, scene.T_world_camera), 1e-6)
          << "input " << index;
      ASSERT_LT(test::translationErrorM(estimate.T_world_camera.pose, scene.T_world_camera), 1e-5)
          << "input " << index;
    }
  }
  // The degenerate sets never determine a pose.
  EXPECT_EQ(converged[static_cast<int>(Damage::kCoincidentPoints)], 0);
  EXPECT_EQ(converged[static_cast<int>(Damage::kCollinearPoints)], 0);
  EXPECT_EQ(converged[static_cast<int>(Damage::kParallelLines)], 0);
  EXPECT_EQ(converged[static_cast<int>(Damage::kConcurrentLines)], 0);
  // Lines through the camera centre alongside a valid scene still converge.
  EXPECT_GT(converged[static_cast<int>(Damage::kLinesThroughCameraCentre)], count / 40);
}

}  // namespace
}  // namespace lineloc
