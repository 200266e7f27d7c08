// Corner matching on the synthetic street: the model corners in view, seen as
// image corners at their true projection plus noise, matched from priors near
// the truth.
#include <gtest/gtest.h>

#include "backbone/matching/corner_matcher.h"
#include "synthetic_street.h"

namespace lineloc {
namespace {

using namespace lineloc::testing;

struct CornerScene {
  std::vector<VisibleCorner> model;
  std::vector<ImageCorner> image;  // image[i] is model[i]'s, then clutter
};

// The street's corners in view of the truth, each seen with noise.
CornerScene cornerScene(std::mt19937& random) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  CornerScene scene;
  scene.model = visibleCorners(render(street, occlusion, 0, random).visible, {});
  scene.image = observeCorners(scene.model, random);
  return scene;
}

PoseWithCovariance tightPrior() {
  PoseWithCovariance prior = truePose();
  prior.covariance = diagonalPoseCovariance(0.02, 0.001);
  return prior;
}

// The image corner the model corner at `model_index` was matched with, or -1.
int matchedImageCorner(const std::vector<CornerMatch>& matches, int model_index) {
  for (const CornerMatch& match : matches) {
    if (match.model_index == model_index) {
      return match.image_index;
    }
  }
  return -1;
}

TEST(CornerMatcher, MatchesEachModelCornerWithItsOwnImageCorner) {
  std::mt19937 random(3);
  CornerScene scene = cornerScene(random);
  ASSERT_GE(scene.model.size(), 10u);
  // Clutter 20 px and more from every corner's projection: window corners.
  std::uniform_real_distribution<double> u(0, 640), v(0, 480);
  while (scene.image.size() < 3 * scene.model.size()) {
    const Eigen::Vector2d pixel(u(random), v(random));
    bool clear = true;
    for (size_t i = 0; i < scene.model.size(); ++i) {
      clear = clear && (scene.image[i].position.cast<double>() - pixel).norm() > 20.0;
    }
    if (clear) {
      scene.image.push_back(cornerAt(pixel));
    }
  }
  const auto matches = matchCorners(scene.image, scene.model, tightPrior(), kCamera, {});
  int matched = 0;
  for (size_t m = 0; m < scene.model.size(); ++m) {
    const int image_index = matchedImageCorner(matches, static_cast<int>(m));
    EXPECT_TRUE(image_index < 0 || image_index == static_cast<int>(m)) << m;
    matched += image_index == static_cast<int>(m) ? 1 : 0;
  }
  // Two model corners can project within a few pixels of each other (a far
  // building's): those are ambiguous. Every other is matched.
  EXPECT_GE(matched, static_cast<int>(scene.model.size()) - 4);
  EXPECT_EQ(matches.size(), static_cast<size_t>(matched));
}

TEST(CornerMatcher, LeavesOutAModelCornerWithTwoImageCornersAlike) {
  std::mt19937 random(4);
  CornerScene scene = cornerScene(random);
  const auto matches = matchCorners(scene.image, scene.model, tightPrior(), kCamera, {});
  ASSERT_FALSE(matches.empty());
  const int model_index = matches.front().model_index;
  // A second image corner as near the projection as the first.
  const Eigen::Vector2d pixel =
      projectPoint(scene.model[model_index].p_world, truePose(), kCamera).pixel;
  const Eigen::Vector2d first = scene.image[model_index].position.cast<double>();
  scene.image.push_back(cornerAt(pixel - (first - pixel)));
  const auto with_twin = matchCorners(scene.image, scene.model, tightPrior(), kCamera, {});
  EXPECT_EQ(matchedImageCorner(with_twin, model_index), -1);
  EXPECT_EQ(with_twin.size(), matches.size() - 1);
}

TEST(CornerMatcher, AnImageCornerNearestTwoModelCornersMatchesNeither) {
  const PoseWithCovariance prior = tightPrior();
  const Eigen::Vector3d a(-8, 40, 12);
  const Eigen::Vector3d b = a + Eigen::Vector3d(0.0, 0.0, 0.1);  // 1.3 px below at 40 m
  const std::vector<VisibleCorner> model = {{a, 1.0, false, {}}, {b, 1.0, false, {}}};
  const Eigen::Vector2d between =
      0.5 * (projectPoint(a, prior, kCamera).pixel + projectPoint(b, prior, kCamera).pixel);
  EXPECT_TRUE(matchCorners({cornerAt(between)}, model, prior, kCamera, {}).empty());
  EXPECT_EQ(matchCorners({cornerAt(between)}, {model[0]}, prior, kCamera, {}).size(), 1u);
}

// 8 px off: beyond the gate of a prior good to 2 cm (at 20 m, under 1 px),
// within that of a prior good to 0.5 m.
TEST(CornerMatcher, GatesByThePredictedCovariance) {
  const Eigen::Vector3d vertex(-8, 20, 12);
  const std::vector<VisibleCorner> model = {{vertex, 1.0, false, {}}};
  PoseWithCovariance prior = tightPrior();
  const std::vector<ImageCorner> image = {
      cornerAt(projectPoint(vertex, prior, kCamera).pixel + Eigen::Vector2d(8.0, 0.0))};
  EXPECT_TRUE(matchCorners(image, model, prior, kCamera, {}).empty());
  prior.covariance = diagonalPoseCovariance(0.5, 0.01);
  EXPECT_EQ(matchCorners(image, model, prior, kCamera, {}).size(), 1u);
}

TEST(CornerMatcher, AModelCornerBehindTheCameraMatchesNothing) {
  const PoseWithCovariance prior = tightPrior();
  const Eigen::Vector3d ahead(-8, 20, 12);
  // Mirrored through the camera centre: it projects to the same pixel.
  const Eigen::Vector3d behind = 2.0 * prior.pose.translation() - ahead;
  const std::vector<ImageCorner> image = {cornerAt(projectPoint(ahead, prior, kCamera).pixel)};
  EXPECT_TRUE(matchCorners(image, {{behind, 1.0, false, {}}}, prior, kCamera, {}).empty());
  EXPECT_EQ(matchCorners(image, {{ahead, 1.0, false, {}}}, prior, kCamera, {}).size(), 1u);
}

}  // namespace
}  // namespace lineloc
