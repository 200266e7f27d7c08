// Model alignment on a synthetic street: the true view of the model lines plus
// noise and clutter (lines not in the model), seen from a perturbed prior.
#include <gtest/gtest.h>

#include <random>

#include "backbone/matching/model_alignment.h"

namespace lineloc {
namespace {

const PinholeCamera kCamera{500, 500, 320, 240, 0, 640, 480};
constexpr double kPixelSigma = 0.5;

struct Street {
  std::vector<FaceRing> faces;
  std::vector<ModelSegment> edges;
};

void addBox(Street& street, double x0, double y0, double x1, double y1, double h) {
  const Eigen::Vector3d c[8] = {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0},
                                {x0, y0, h}, {x1, y0, h}, {x1, y1, h}, {x0, y1, h}};
  const std::vector<FaceRing> faces = {{c[0], c[3], c[2], c[1]}, {c[4], c[5], c[6], c[7]},
                                       {c[0], c[1], c[5], c[4]}, {c[1], c[2], c[6], c[5]},
                                       {c[2], c[3], c[7], c[6]}, {c[3], c[0], c[4], c[7]}};
  street.faces.insert(street.faces.end(), faces.begin(), faces.end());
  const int pairs[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                            {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (const auto& pair : pairs) {
    street.edges.push_back({static_cast<int64_t>(street.edges.size()), 0, c[pair[0]], c[pair[1]]});
  }
}

// Two rows of buildings of different heights along a street running north.
Street makeStreet() {
  Street street;
  const double heights[] = {12, 18, 9, 15, 21, 11};
  for (int i = 0; i < 6; ++i) {
    addBox(street, -20, 10 + 25 * i, -8, 30 + 25 * i, heights[i]);
    addBox(street, 8, 5 + 25 * i, 22, 27 + 25 * i, heights[5 - i]);
  }
  return street;
}

PoseWithCovariance truePose() {
  Eigen::Matrix3d R_world_camera;  // looking north, level, camera 1.5 m up
  R_world_camera << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  PoseWithCovariance pose;
  pose.pose.linear() =
      Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R_world_camera;
  pose.pose.translation() = Eigen::Vector3d(1.0, 0.0, 1.5);
  return pose;
}

ImageSegment observe(const Eigen::Vector2d& a, const Eigen::Vector2d& b, std::mt19937& random) {
  std::normal_distribution<double> noise(0.0, kPixelSigma);
  ImageSegment segment;
  segment.start = (a + Eigen::Vector2d(noise(random), noise(random))).cast<float>();
  segment.end = (b + Eigen::Vector2d(noise(random), noise(random))).cast<float>();
  segment.start_covariance = Eigen::Matrix2f::Identity() * kPixelSigma * kPixelSigma;
  segment.end_covariance = segment.start_covariance;
  return segment;
}

struct Scene {
  std::vector<VisibleSegment> visible;
  std::vector<ImageSegment> image;
};

// What the camera sees at the true pose: every visible model piece, plus
// `clutter` segments that are in no model (window frames: short, vertical or
// horizontal like the façade lines, anywhere in the image).
Scene render(const Street& street, const OcclusionScene& occlusion, int clutter,
             std::mt19937& random) {
  Scene scene;
  const PoseWithCovariance truth = truePose();
  scene.visible = visibleSegments(street.edges, occlusion, truth, kCamera, {});
  for (const VisibleSegment& segment : scene.visible) {
    const ProjectedSegment p =
        projectSegment(segment.start_world, segment.end_world, truth, kCamera);
    scene.image.push_back(observe(p.start_px, p.end_px, random));
  }
  std::uniform_real_distribution<double> u(40, 600), v(40, 440);
  for (int i = 0; i < clutter; ++i) {
    const Eigen::Vector2d a(u(random), v(random));
    const bool vertical = i % 2 == 0;
    const Eigen::Vector2d b = a + (vertical ? Eigen::Vector2d(0, 30) : Eigen::Vector2d(30, 0));
    scene.image.push_back(observe(a, b, random));
  }
  return scene;
}

PoseWithCovariance perturbedPrior(const PoseWithCovariance& truth, std::mt19937& random,
                                  double position_sigma, double rotation_sigma) {
  std::normal_distribution<double> n(0.0, 1.0);
  PoseWithCovariance prior = truth;
  prior.pose.translation() +=
      position_sigma * Eigen::Vector3d(n(random), n(random), 0.3 * n(random));
  prior.pose.linear() =
      Eigen::AngleAxisd(rotation_sigma * n(random), Eigen::Vector3d::UnitZ()).toRotationMatrix() *
      prior.pose.linear();
  prior.covariance = diagonalPoseCovariance(2 * position_sigma, 2 * rotation_sigma);
  return prior;
}

// e^T Sigma^-1 e of the estimate against the truth, e = [dp; dtheta].
double normalizedErrorSquared(const PoseWithCovariance& estimate, const PoseWithCovariance& truth) {
  Eigen::Matrix<double, 6, 1> error;
  error.head<3>() = truth.pose.translation() - estimate.pose.translation();
  const Eigen::AngleAxisd rotation(truth.pose.linear() * estimate.pose.linear().transpose());
  error.tail<3>() = rotation.angle() * rotation.axis();
  return error.dot(estimate.covariance.ldlt().solve(error));
}

// chi^2 with 6 degrees of freedom at 99.9 %: a consistent estimate exceeds it
// once in a thousand trials.
constexpr double kChi2Six999 = 22.46;

TEST(ModelAlignment, RecoversThePoseConsistentlyWithItsCovariance) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces);
  std::mt19937 random(7);
  for (int trial = 0; trial < 10; ++trial) {
    const Scene scene = render(street, occlusion, 0, random);
    const PoseWithCovariance prior = perturbedPrior(truePose(), random, 0.3, 0.01);
    const Alignment alignment = alignModel(scene.image, scene.visible, prior, kCamera, {});
    ASSERT_EQ(alignment.status, AlignmentStatus::kOk) << alignment.message;
    EXPECT_LT(normalizedErrorSquared(alignment.T_world_camera, truePose()), kChi2Six999);
    // And the covariance is a fix, not a shrug: 0.5 px on lines 10-150 m away.
    EXPECT_LT(std::sqrt(alignment.T_world_camera.covariance.topLeftCorner<3, 3>().trace()), 0.2);
  }
}

TEST(ModelAlignment, ClutterNotInTheModelDoesNotPullThePose) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces);
  std::mt19937 random(11);
  for (int trial = 0; trial < 10; ++trial) {
    Scene scene = render(street, occlusion, 0, random);
    const int model_lines = static_cast<int>(scene.image.size());
    // 30 % of the image lines come from things not in the model.
    scene = render(street, occlusion, model_lines * 3 / 7, random);
    const PoseWithCovariance prior = perturbedPrior(truePose(), random, 0.3, 0.01);
    const Alignment alignment = alignModel(scene.image, scene.visible, prior, kCamera, {});
    ASSERT_EQ(alignment.status, AlignmentStatus::kOk) << alignment.message;
    EXPECT_LT(normalizedErrorSquared(alignment.T_world_camera, truePose()), kChi2Six999);
  }
}

TEST(ModelAlignment, ASingleFacadeIsReportedIllConditionedNotPrecise) {
  Street wall;
  addBox(wall, 8, -50, 9, 200, 10);  // one long façade along the street, featureless
  const OcclusionScene occlusion(wall.faces);
  std::mt19937 random(3);
  const Scene scene = render(wall, occlusion, 0, random);
  const PoseWithCovariance prior = perturbedPrior(truePose(), random, 0.3, 0.01);
  const Alignment alignment = alignModel(scene.image, scene.visible, prior, kCamera, {});
  EXPECT_NE(alignment.status, AlignmentStatus::kOk) << alignment.message;
}

TEST(ModelAlignment, NothingToMatchIsTooFewMatches) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces);
  std::mt19937 random(5);
  const Scene scene = render(street, occlusion, 0, random);
  const Alignment alignment = alignModel({}, scene.visible, truePose(), kCamera, {});
  EXPECT_EQ(alignment.status, AlignmentStatus::kTooFewMatches);
}

}  // namespace
}  // namespace lineloc
