// Model alignment on a synthetic street: the true view of the model lines plus
// noise and clutter (lines not in the model), seen from a perturbed prior.
#include <gtest/gtest.h>

#include "backbone/matching/model_alignment.h"
#include "synthetic_street.h"

namespace lineloc {
namespace {

using namespace lineloc::testing;

TEST(ModelAlignment, RecoversThePoseConsistentlyWithItsCovariance) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  std::mt19937 random(7);
  for (int trial = 0; trial < 10; ++trial) {
    const Scene scene = render(street, occlusion, 0, random);
    const PoseWithCovariance prior = perturbedPrior(truePose(), random, 0.3, 0.01);
    const Alignment alignment = alignModel(scene.image, scene.visible, prior, kCamera, {});
    ASSERT_EQ(alignment.status, AlignmentStatus::kOk) << alignment.message;
    EXPECT_LT(normalizedErrorSquared(alignment.T_world_camera, truePose().pose), kChi2Six999);
    // And the covariance is a fix, not a shrug: 0.5 px on lines 10-150 m away.
    EXPECT_LT(std::sqrt(alignment.T_world_camera.covariance.topLeftCorner<3, 3>().trace()), 0.2);
  }
}

TEST(ModelAlignment, ClutterNotInTheModelDoesNotPullThePose) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  std::mt19937 random(11);
  for (int trial = 0; trial < 10; ++trial) {
    Scene scene = render(street, occlusion, 0, random);
    const int model_lines = static_cast<int>(scene.image.size());
    // 30 % of the image lines come from things not in the model.
    scene = render(street, occlusion, model_lines * 3 / 7, random);
    const PoseWithCovariance prior = perturbedPrior(truePose(), random, 0.3, 0.01);
    const Alignment alignment = alignModel(scene.image, scene.visible, prior, kCamera, {});
    ASSERT_EQ(alignment.status, AlignmentStatus::kOk) << alignment.message;
    EXPECT_LT(normalizedErrorSquared(alignment.T_world_camera, truePose().pose), kChi2Six999);
  }
}

TEST(ModelAlignment, ASingleFacadeIsReportedIllConditionedNotPrecise) {
  Street wall;
  addBox(wall, 8, -50, 9, 200, 10);  // one long façade along the street, featureless
  const OcclusionScene occlusion(wall.faces, wall.face_building_ids);
  std::mt19937 random(3);
  const Scene scene = render(wall, occlusion, 0, random);
  const PoseWithCovariance prior = perturbedPrior(truePose(), random, 0.3, 0.01);
  const Alignment alignment = alignModel(scene.image, scene.visible, prior, kCamera, {});
  EXPECT_NE(alignment.status, AlignmentStatus::kOk) << alignment.message;
}

TEST(ModelAlignment, NothingToMatchIsTooFewMatches) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  std::mt19937 random(5);
  const Scene scene = render(street, occlusion, 0, random);
  const Alignment alignment = alignModel({}, scene.visible, truePose(), kCamera, {});
  EXPECT_EQ(alignment.status, AlignmentStatus::kTooFewMatches);
}

TEST(ModelAlignment, AnOkAnswerIsWidenedForTheRedundancyOfItsInliers) {
  Alignment alignment;
  alignment.status = AlignmentStatus::kOk;
  alignment.inliers = 14;
  alignment.T_world_camera.covariance = diagonalPoseCovariance(0.1, 0.01);
  Alignment ambiguous = alignment;
  ambiguous.status = AlignmentStatus::kAmbiguous;

  widenForConfidence(alignment, 0.9973);
  widenForConfidence(ambiguous, 0.9973);
  // 6 F_{6,22}(0.9973) / chi^2_6(0.9973) for 2 * 14 - 6 = 22 residual degrees.
  EXPECT_NEAR(alignment.T_world_camera.covariance(0, 0) / 0.01, 1.45, 0.01);
  EXPECT_NEAR(alignment.T_world_camera.covariance(5, 5) / 1e-4, 1.45, 0.01);
  EXPECT_EQ(ambiguous.T_world_camera.covariance, diagonalPoseCovariance(0.1, 0.01));
}

}  // namespace
}  // namespace lineloc
