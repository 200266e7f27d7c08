// Model alignment on a synthetic street: the true view of the model lines plus
// noise and clutter (lines not in the model), seen from a perturbed prior.
#include <gtest/gtest.h>

#include <limits>

#include "backbone/matching/model_alignment.h"
#include "backbone/visibility/visible_corners.h"
#include "db/citymodel/line_extraction.h"
#include "synthetic_street.h"

namespace lineloc {
namespace {

using namespace lineloc::testing;

constexpr int kGroundKind = static_cast<int>(citymodel::LineKind::kGround);

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

// The scene's segments along the street (y) and one vertical edge, which
// alone fixes the position along the street, a few decimetres at best.
std::vector<ImageSegment> segmentsAlongTheStreet(const Scene& scene) {
  std::vector<ImageSegment> kept;
  bool vertical_kept = false;
  for (size_t i = 0; i < scene.visible.size(); ++i) {
    const VisibleSegment& piece = scene.visible[i];
    const Eigen::Vector3d direction = (piece.end_world - piece.start_world).normalized();
    const bool vertical = std::abs(direction.z()) > 0.98;
    if (std::abs(direction.y()) > 0.98 || (vertical && !vertical_kept)) {
      kept.push_back(scene.image[i]);
      vertical_kept = vertical_kept || vertical;
    }
  }
  return kept;
}

// Options under which that street's lines alone are ill-conditioned.
AlignmentOptions alongTheStreetOptions() {
  AlignmentOptions options;
  options.max_position_sigma_m = 0.2;
  return options;
}

TEST(ModelAlignment, CornersFixThePositionTheLinesLeaveOpen) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  std::mt19937 random(13);
  std::uniform_real_distribution<double> u(0, 640), v(0, 480);
  const AlignmentOptions options = alongTheStreetOptions();
  for (int trial = 0; trial < 10; ++trial) {
    Scene scene = render(street, occlusion, 0, random);
    scene.image = segmentsAlongTheStreet(scene);
    const std::vector<VisibleCorner> model_corners = visibleCorners(scene.visible, {});
    std::vector<ImageCorner> image_corners = observeCorners(model_corners, random);
    while (image_corners.size() < model_corners.size() * 10 / 7) {
      image_corners.push_back(cornerAt({u(random), v(random)}));
    }
    const PoseWithCovariance prior = perturbedPrior(truePose(), random, 0.1, 0.003);
    const Alignment lines_only = alignModel(scene.image, scene.visible, prior, kCamera, options);
    ASSERT_EQ(lines_only.status, AlignmentStatus::kIllConditioned) << lines_only.message;
    const Alignment alignment =
        completeWithCorners(lines_only, {scene.image, image_corners, scene.visible, model_corners},
                            prior, kCamera, options);
    ASSERT_EQ(alignment.status, AlignmentStatus::kOk) << alignment.message;
    EXPECT_LT(normalizedErrorSquared(alignment.T_world_camera, truePose().pose), kChi2Six999);
  }
}

TEST(ModelAlignment, CornersLeaveAPoseTheLinesDetermineAlone) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  std::mt19937 random(17);
  for (int trial = 0; trial < 5; ++trial) {
    const Scene scene = render(street, occlusion, 0, random);
    const std::vector<VisibleCorner> model_corners = visibleCorners(scene.visible, {});
    // Every corner 3 px to the right of its vertex: matched, they would pull.
    std::vector<ImageCorner> image_corners = observeCorners(model_corners, random);
    for (ImageCorner& corner : image_corners) {
      corner.position.x() += 3.0f;
    }
    const PoseWithCovariance prior = perturbedPrior(truePose(), random, 0.1, 0.003);
    const Alignment lines_only = alignModel(scene.image, scene.visible, prior, kCamera, {});
    ASSERT_EQ(lines_only.status, AlignmentStatus::kOk) << lines_only.message;
    const Alignment alignment = completeWithCorners(
        lines_only, {scene.image, image_corners, scene.visible, model_corners}, prior, kCamera, {});
    EXPECT_TRUE(alignment.T_world_camera.pose.isApprox(lines_only.T_world_camera.pose));
    EXPECT_EQ(alignment.inliers, lines_only.inliers);
  }
}

// A street whose buildings stand 0.2 m lower in the model than the pavement
// meets them (a flat pavement at the terrain's median, bases spread about it):
// the image shows every wall's foot 0.2 m above the model's ground line.
Scene withRaisedFeet(const Street& street, const OcclusionScene& occlusion, std::mt19937& random) {
  Scene scene = render(street, occlusion, 0, random);
  const Eigen::Vector3d raised(0.0, 0.0, 0.2);
  for (size_t i = 0; i < scene.visible.size(); ++i) {
    const VisibleSegment& line = scene.visible[i];
    if (line.start_world.z() != 0.0 || line.end_world.z() != 0.0) {
      continue;  // not a wall's foot
    }
    const ProjectedSegment p =
        projectSegment(line.start_world + raised, line.end_world + raised, truePose(), kCamera);
    scene.image[i] = observe(p.start_px, p.end_px, random);
  }
  return scene;
}

TEST(ModelAlignment, GroundLinesOffTheWallFeetDoNotPullThePose) {
  Street street = makeStreet();
  for (ModelSegment& edge : street.edges) {
    if (edge.start_world.z() == 0.0 && edge.end_world.z() == 0.0) {
      edge.kind = kGroundKind;
    }
  }
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  AlignmentOptions ground_as_surveyed;
  ground_as_surveyed.ground_line_sigma_m = ground_as_surveyed.model_sigma_m;
  std::mt19937 random(13);
  double height_error_m = 0.0;
  double height_error_surveyed_m = 0.0;
  for (int trial = 0; trial < 10; ++trial) {
    const Scene scene = withRaisedFeet(street, occlusion, random);
    const PoseWithCovariance prior = perturbedPrior(truePose(), random, 0.1, 0.01);
    const Alignment alignment = alignModel(scene.image, scene.visible, prior, kCamera, {});
    const Alignment surveyed =
        alignModel(scene.image, scene.visible, prior, kCamera, ground_as_surveyed);
    ASSERT_EQ(alignment.status, AlignmentStatus::kOk) << alignment.message;
    EXPECT_LT(normalizedErrorSquared(alignment.T_world_camera, truePose().pose), kChi2Six999);
    height_error_m += std::abs(alignment.T_world_camera.pose.translation().z() - 1.5);
    height_error_surveyed_m += std::abs(surveyed.T_world_camera.pose.translation().z() - 1.5);
  }
  // Taken as surveyed as the roofs, the feet pull the camera down towards them.
  EXPECT_LT(height_error_m, 0.5 * height_error_surveyed_m);
}

// Learnt lines (LineKind::kLearnt) 0.2 m below where the image shows them,
// as uncertain as learnt lines can be: they pull the pose in proportion to
// their own standard deviation, and one that claims to be exact is taken no
// more surely than a surveyed model line.
TEST(ModelAlignment, LearntLinesPullThePoseByTheirOwnUncertainty) {
  const auto streetWithLearntFeet = [](double sigma_m) {
    Street street = makeStreet();
    for (ModelSegment& edge : street.edges) {
      if (edge.start_world.z() == 0.0 && edge.end_world.z() == 0.0) {
        edge.kind = static_cast<int>(citymodel::LineKind::kLearnt);
        edge.sigma_m = sigma_m;
      }
    }
    return street;
  };
  const Street uncertain = streetWithLearntFeet(0.15);
  const Street exact = streetWithLearntFeet(0.0);
  const Street as_surveyed = streetWithLearntFeet(AlignmentOptions{}.model_sigma_m);
  const OcclusionScene occlusion(uncertain.faces, uncertain.face_building_ids);
  double uncertain_error_m = 0.0;
  double exact_error_m = 0.0;
  for (int trial = 0; trial < 10; ++trial) {
    std::mt19937 random(31 + trial);
    const auto align = [&](const Street& street) {
      std::mt19937 same(random);
      const Scene scene = withRaisedFeet(street, occlusion, same);
      const PoseWithCovariance prior = perturbedPrior(truePose(), same, 0.1, 0.01);
      return alignModel(scene.image, scene.visible, prior, kCamera, {});
    };
    const Alignment with_uncertain = align(uncertain);
    const Alignment with_exact = align(exact);
    const Alignment with_surveyed = align(as_surveyed);
    ASSERT_EQ(with_uncertain.status, AlignmentStatus::kOk) << with_uncertain.message;
    ASSERT_EQ(with_exact.status, AlignmentStatus::kOk) << with_exact.message;
    EXPECT_TRUE(with_exact.T_world_camera.pose.isApprox(with_surveyed.T_world_camera.pose, 1e-9));
    uncertain_error_m += std::abs(with_uncertain.T_world_camera.pose.translation().z() - 1.5);
    exact_error_m += std::abs(with_exact.T_world_camera.pose.translation().z() - 1.5);
  }
  EXPECT_LT(uncertain_error_m, 0.5 * exact_error_m);
}

// Where window frames lie beside the building edges in the image: to the
// right, or on the side of the line's own façade (none beside a crease).
enum class Beside { kRight, kFacadeSide };

// Window frames beside the building edges: every vertical model line's image
// edge has a parallel one offset_px beside it, and for every other one the
// building edge itself is not seen (a corner the image does not show).
Scene withDetailBesideTheEdges(const Street& street, const OcclusionScene& occlusion,
                               double offset_px, Beside side, std::mt19937& random) {
  Scene scene = render(street, occlusion, 0, random);
  int vertical_lines = 0;
  for (size_t i = 0; i < scene.visible.size(); ++i) {
    const VisibleSegment& line = scene.visible[i];
    const Eigen::Vector3d direction = (line.end_world - line.start_world).normalized();
    if (std::abs(direction.z()) < 0.99 || (side == Beside::kFacadeSide && line.facade_side == 0)) {
      continue;
    }
    const ProjectedSegment p =
        projectSegment(line.start_world, line.end_world, truePose(), kCamera);
    const Eigen::Vector2d along = (p.end_px - p.start_px).normalized();
    // The left normal (image, y down) of (dx, dy) is (dy, -dx).
    const Eigen::Vector2d beside =
        side == Beside::kRight
            ? Eigen::Vector2d(offset_px, 0.0)
            : offset_px * line.facade_side * Eigen::Vector2d(along.y(), -along.x());
    const ImageSegment frame = observe(p.start_px + beside, p.end_px + beside, random);
    if (++vertical_lines % 2 == 0) {
      scene.image[i] = frame;
    } else {
      scene.image.push_back(frame);
    }
  }
  return scene;
}

double positionErrorM(const Alignment& alignment) {
  return (alignment.T_world_camera.pose.translation() - truePose().pose.translation()).norm();
}

// Detail 3 px beside the edges lies 2-5 standard deviations off, as it does
// on the simulated Delft frames (model_alignment.h, loss_scale_sigma).
TEST(ModelAlignment, DetailBesideTheBuildingEdgesPullsThePoseLessThanWithAWideLoss) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  AlignmentOptions wide_loss;
  wide_loss.loss_scale_sigma = 2.0;
  std::mt19937 random(17);
  double error_m = 0.0;
  double error_wide_loss_m = 0.0;
  for (int trial = 0; trial < 10; ++trial) {
    const Scene scene = withDetailBesideTheEdges(street, occlusion, 3.0, Beside::kRight, random);
    const PoseWithCovariance prior = perturbedPrior(truePose(), random, 0.1, 0.01);
    const Alignment alignment = alignModel(scene.image, scene.visible, prior, kCamera, {});
    const Alignment wide = alignModel(scene.image, scene.visible, prior, kCamera, wide_loss);
    ASSERT_EQ(alignment.status, AlignmentStatus::kOk) << alignment.message;
    EXPECT_LT(normalizedErrorSquared(alignment.T_world_camera, truePose().pose), kChi2Six999);
    error_m += positionErrorM(alignment);
    error_wide_loss_m += positionErrorM(wide);
  }
  EXPECT_LT(error_m, 0.7 * error_wide_loss_m);
}

// The position error along the camera's view (m, positive ahead).
double errorAlongViewM(const Alignment& alignment) {
  const Eigen::Isometry3d& truth = truePose().pose;
  return truth.linear().col(2).dot(alignment.T_world_camera.pose.translation() -
                                   truth.translation());
}

// Detail 1.5 px beside the building edges on their façades' side lies 1.5-2.5
// standard deviations off (0.5 px image noise, a 0.3 px floor, 3 cm of survey
// error at 10-150 m), where the Cauchy loss still gives it most of an inlier's
// pull. The façades lie outward on both sides of the street, so the detail
// spreads the view and holds the pose ahead of the truth. Leaving such matches
// out takes the pose back to the edges: over 20 trials the mean error along
// the view, whose noise is about 4 cm per trial (0.9 cm for the mean), falls
// by more than half (4.9 to 2.0 cm).
TEST(ModelAlignment, DetailOnTheFacadeSideOfBuildingEdgesIsLeftOut) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  AlignmentOptions uncut;
  uncut.facade_side_cut_sigma = std::numeric_limits<double>::infinity();
  std::mt19937 random(19);
  constexpr int kTrials = 20;
  double ahead_m = 0.0;
  double ahead_uncut_m = 0.0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const Scene scene =
        withDetailBesideTheEdges(street, occlusion, 1.5, Beside::kFacadeSide, random);
    const PoseWithCovariance prior = perturbedPrior(truePose(), random, 0.1, 0.01);
    const Alignment alignment = alignModel(scene.image, scene.visible, prior, kCamera, {});
    const Alignment without_cut = alignModel(scene.image, scene.visible, prior, kCamera, uncut);
    ASSERT_EQ(alignment.status, AlignmentStatus::kOk) << alignment.message;
    EXPECT_LT(normalizedErrorSquared(alignment.T_world_camera, truePose().pose), kChi2Six999);
    ahead_m += errorAlongViewM(alignment) / kTrials;
    ahead_uncut_m += errorAlongViewM(without_cut) / kTrials;
  }
  EXPECT_GT(ahead_uncut_m, 0.03);
  EXPECT_LT(std::abs(ahead_m), 0.5 * ahead_uncut_m);
}

// The cut only sharpens an OK answer. A threshold far on the other side of
// every line cuts all the matches that have a façade side: of the street's 40
// inliers, 16 matches stay, too few when 20 are needed. The alignment keeps
// the pose its rounds converged to, and counts the cut's round.
TEST(ModelAlignment, ACutThatLeavesTooFewMatchesKeepsTheConvergedAnswer) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  std::mt19937 random(7);
  const Scene scene = render(street, occlusion, 0, random);
  const PoseWithCovariance prior = perturbedPrior(truePose(), random, 0.03, 0.003);
  AlignmentOptions uncut;
  uncut.min_inliers = 20;
  uncut.facade_side_cut_sigma = std::numeric_limits<double>::infinity();
  AlignmentOptions cut_all = uncut;
  cut_all.facade_side_cut_sigma = -1e6;
  const Alignment converged = alignModel(scene.image, scene.visible, prior, kCamera, uncut);
  const Alignment kept = alignModel(scene.image, scene.visible, prior, kCamera, cut_all);
  ASSERT_EQ(converged.status, AlignmentStatus::kOk) << converged.message;
  EXPECT_EQ(kept.status, AlignmentStatus::kOk) << kept.message;
  EXPECT_EQ(kept.rounds, converged.rounds + 1);
  EXPECT_EQ(kept.inliers, converged.inliers);
  EXPECT_TRUE(kept.T_world_camera.pose.isApprox(converged.T_world_camera.pose, 0.0));
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
