// Acquisition from a DGPS-quality prior on the synthetic street: the search
// finds the camera metres away and the aligned pose is consistent with its
// covariance, narrow enough for tracking to start from; clutter does not
// change that; a view that cannot tell poses apart is never answered with a
// precise pose.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "backbone/matching/localizer.h"
#include "backbone/matching/pose_acquisition.h"
#include "synthetic_street.h"

namespace lineloc {
namespace {

using namespace lineloc::testing;

// DGPS: 4 m per horizontal axis; the height comes from the ground (10 cm);
// yaw from a compass-aided filter (0.5 degrees).
constexpr double kPriorPositionSigmaM = 4.0;
constexpr double kPriorHeightSigmaM = 0.1;
constexpr double kPriorYawSigmaRad = 0.5 * M_PI / 180.0;

PoseWithCovariance dgpsPrior(std::mt19937& random) {
  std::normal_distribution<double> n(0.0, 1.0);
  PoseWithCovariance prior = truePose();
  prior.pose.translation() +=
      Eigen::Vector3d(kPriorPositionSigmaM * n(random), kPriorPositionSigmaM * n(random),
                      kPriorHeightSigmaM * n(random));
  prior.pose.linear() = Eigen::AngleAxisd(kPriorYawSigmaRad * n(random), Eigen::Vector3d::UnitZ())
                            .toRotationMatrix() *
                        prior.pose.linear();
  prior.covariance = diagonalPoseCovariance(kPriorPositionSigmaM, kPriorYawSigmaRad);
  prior.covariance(2, 2) = kPriorHeightSigmaM * kPriorHeightSigmaM;
  return prior;
}

// The truth's pose, known to 0.5 m horizontally and to the ground's 0.1 m in
// height: a prior close enough for one search to settle the camera.
PoseWithCovariance nearPrior(const Eigen::Vector3d& offset_m) {
  PoseWithCovariance prior = truePose();
  prior.pose.translation() += offset_m;
  prior.covariance = diagonalPoseCovariance(0.5, kPriorYawSigmaRad);
  prior.covariance(2, 2) = kPriorHeightSigmaM * kPriorHeightSigmaM;
  return prior;
}

// Trials each acquisition must answer with a consistent pose; ambiguity is
// allowed (the street repeats), a wrong precise pose is not.
void expectConsistentOrAmbiguous(int clutter_percent, uint32_t seed) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  std::mt19937 random(seed);
  int ok = 0;
  constexpr int kTrials = 6;
  for (int trial = 0; trial < kTrials; ++trial) {
    Scene scene = render(street, occlusion, 0, random);
    const int clutter =
        static_cast<int>(scene.image.size()) * clutter_percent / (100 - clutter_percent);
    scene = render(street, occlusion, clutter, random);
    const Acquisition acquisition = acquirePose(scene.image, street.edges, occlusion,
                                                dgpsPrior(random), kCamera, AcquisitionOptions{});
    if (acquisition.alignment.status != AlignmentStatus::kOk) {
      EXPECT_EQ(acquisition.alignment.status, AlignmentStatus::kAmbiguous)
          << acquisition.alignment.message;
      continue;
    }
    ++ok;
    EXPECT_LT(normalizedErrorSquared(acquisition.alignment.T_world_camera, truePose().pose),
              kChi2Six999);
    // Its covariance is a start that tracking takes.
    EXPECT_FALSE(needsAcquisition(acquisition.alignment.T_world_camera, LocalizerOptions{}));
  }
  // The street has distinct building heights: most views are unambiguous.
  EXPECT_GE(ok, kTrials / 2);
}

TEST(PoseAcquisition, FindsTheCameraMetresFromTheDgpsPrior) {
  expectConsistentOrAmbiguous(0, 21);
}

TEST(PoseAcquisition, ThirtyPercentClutterChangesNothing) {
  expectConsistentOrAmbiguous(30, 23);
}

TEST(PoseAcquisition, AFeaturelessFacadeIsNeverAPrecisePose) {
  Street wall;
  addBox(wall, 8, -50, 9, 200, 10);  // along the street, nothing to place the camera along it
  const OcclusionScene occlusion(wall.faces, wall.face_building_ids);
  std::mt19937 random(5);
  const Scene scene = render(wall, occlusion, 0, random);
  const Acquisition acquisition = acquirePose(scene.image, wall.edges, occlusion, dgpsPrior(random),
                                              kCamera, AcquisitionOptions{});
  EXPECT_NE(acquisition.alignment.status, AlignmentStatus::kOk) << acquisition.alignment.message;
}

// A prior 0.4 m above the camera, sure of its height to 0.1 m: the
// hypotheses start at that height, and the alignments that reach the truth
// lie four of its sigmas below it, which the prior rules out.
TEST(PoseAcquisition, AnAlignmentFarFromThePriorsHeightIsNotTheCamera) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  std::mt19937 random(21);
  const Scene scene = render(street, occlusion, 0, random);
  const PoseWithCovariance prior = nearPrior(Eigen::Vector3d(0.0, 0.0, 0.4));
  AcquisitionOptions ungated;
  ungated.height_gate_sigmas = std::numeric_limits<double>::infinity();
  const Acquisition found =
      acquirePose(scene.image, street.edges, occlusion, prior, kCamera, ungated);
  ASSERT_EQ(found.alignment.status, AlignmentStatus::kOk) << found.alignment.message;
  EXPECT_LT(std::abs(found.alignment.T_world_camera.pose.translation().z() -
                     truePose().pose.translation().z()),
            0.1);
  const Acquisition gated =
      acquirePose(scene.image, street.edges, occlusion, prior, kCamera, AcquisitionOptions{});
  EXPECT_NE(gated.alignment.status, AlignmentStatus::kOk) << gated.alignment.message;
}

// The same view, with the floor just above what its best aligned pose
// scores, is not answered: no rival is needed for a weak view to be turned
// down.
TEST(PoseAcquisition, ABestScoringUnderTheFloorIsNotAnswered) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  std::mt19937 random(21);
  const Scene scene = render(street, occlusion, 0, random);
  const PoseWithCovariance prior = nearPrior(Eigen::Vector3d::Zero());
  const Acquisition found =
      acquirePose(scene.image, street.edges, occlusion, prior, kCamera, AcquisitionOptions{});
  ASSERT_EQ(found.alignment.status, AlignmentStatus::kOk) << found.alignment.message;
  AcquisitionOptions demanding;
  demanding.min_verification_score =
      std::nextafter(found.summary.best_score, std::numeric_limits<double>::infinity());
  const Acquisition weak =
      acquirePose(scene.image, street.edges, occlusion, prior, kCamera, demanding);
  EXPECT_EQ(weak.alignment.status, AlignmentStatus::kTooFewMatches) << weak.alignment.message;
  EXPECT_EQ(weak.summary.best_score, found.summary.best_score);
}

// A step half as strong as the faintest a search takes.
float faintContrast(const AcquisitionOptions& options) {
  return 0.5f * static_cast<float>(options.min_segment_contrast);
}

// The same view with every step fainter than searches take (walls in shade
// meeting each other and the street): a search takes none of it, tracking
// from a prior it can track from aligns on all of it.
TEST(PoseAcquisition, FaintSegmentsAreLeftToTracking) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  std::mt19937 random(21);
  Scene scene = render(street, occlusion, 0, random);
  const LocalizerOptions options;
  for (ImageSegment& segment : scene.image) {
    segment.contrast = faintContrast(options.acquisition);
  }
  const Acquisition searched =
      acquirePose(scene.image, street.edges, occlusion, nearPrior(Eigen::Vector3d::Zero()), kCamera,
                  options.acquisition);
  EXPECT_EQ(searched.alignment.status, AlignmentStatus::kTooFewMatches)
      << searched.alignment.message;
  const PoseWithCovariance trackable = perturbedPrior(truePose(), random, 0.03, 0.001);
  ASSERT_FALSE(needsAcquisition(trackable, options));
  const Localization tracked =
      localize(scene.image, {}, street.edges, occlusion, trackable, kCamera, options);
  ASSERT_EQ(tracked.alignment.status, AlignmentStatus::kOk) << tracked.alignment.message;
  EXPECT_LT(normalizedErrorSquared(tracked.alignment.T_world_camera, truePose().pose), kChi2Six999);
}

// The view, and faint lines of the view from 1.2 m along the street (window
// frames, shadows, parked cars: things in no model that a front end keeping
// the walls in shade keeps too): the search answers the camera, and does not
// when it takes the faint lines as well.
TEST(PoseAcquisition, FaintLinesOfAViewBesideDoNotRivalTheCamera) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  std::mt19937 random(21);
  Scene scene = render(street, occlusion, 0, random);
  const AcquisitionOptions options;
  PoseWithCovariance beside = truePose();
  beside.pose.translation() += Eigen::Vector3d(0.0, 1.2, 0.0);
  for (const VisibleSegment& segment :
       visibleSegments(street.edges, occlusion, beside, kCamera, {})) {
    const ProjectedSegment p =
        projectSegment(segment.start_world, segment.end_world, beside, kCamera);
    ImageSegment faint = observe(p.start_px, p.end_px, random);
    faint.contrast = faintContrast(options);
    scene.image.push_back(faint);
  }
  const PoseWithCovariance prior = nearPrior(Eigen::Vector3d(0.0, 0.6, 0.0));
  const Acquisition found =
      acquirePose(scene.image, street.edges, occlusion, prior, kCamera, options);
  ASSERT_EQ(found.alignment.status, AlignmentStatus::kOk) << found.alignment.message;
  EXPECT_LT(normalizedErrorSquared(found.alignment.T_world_camera, truePose().pose), kChi2Six999);
  AcquisitionOptions taking_all = options;
  taking_all.min_segment_contrast = 0.0;
  const Acquisition confused =
      acquirePose(scene.image, street.edges, occlusion, prior, kCamera, taking_all);
  EXPECT_NE(confused.alignment.status, AlignmentStatus::kOk) << confused.alignment.message;
}

// The view with cables across the street every 2 m from 10 to 40 m ahead,
// 7-9 m up (lines in no model, in its open sky): a search still answers the
// camera, as its clear sky shows them to be clutter; counted as in a
// typical street's sky, they sink its score under the floor.
TEST(PoseAcquisition, CablesInItsSkyDoNotRejectTheCamera) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  std::mt19937 random(21);
  Scene scene = render(street, occlusion, 0, random);
  std::uniform_real_distribution<double> height_m(7.0, 9.0);
  for (double y = 10.0; y < 40.0; y += 2.0) {
    const double z = height_m(random);
    const ProjectedSegment cable = projectSegment({-8.0, y, z}, {8.0, y, z}, truePose(), kCamera);
    scene.image.push_back(observe(cable.start_px, cable.end_px, random));
  }
  const PoseWithCovariance prior = nearPrior(Eigen::Vector3d(0.0, 0.6, 0.0));
  const AcquisitionOptions options;
  const Acquisition found =
      acquirePose(scene.image, street.edges, occlusion, prior, kCamera, options);
  ASSERT_EQ(found.alignment.status, AlignmentStatus::kOk) << found.alignment.message;
  EXPECT_LT(normalizedErrorSquared(found.alignment.T_world_camera, truePose().pose), kChi2Six999);
  AcquisitionOptions strict = options;
  strict.sky_edges.min_clear_area_px2 = std::numeric_limits<double>::infinity();
  const Acquisition rejected =
      acquirePose(scene.image, street.edges, occlusion, prior, kCamera, strict);
  EXPECT_EQ(rejected.alignment.status, AlignmentStatus::kTooFewMatches)
      << rejected.alignment.message;
}

// The same view seen by a camera of four times the resolution (the same
// field of view, every pixel coordinate and its uncertainty scaled): the
// search decides alike, at the same pose, with the same score.
TEST(PoseAcquisition, DecidesAlikeAtFourTimesTheResolution) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  std::mt19937 random(23);
  Scene scene = render(street, occlusion, 0, random);
  scene = render(street, occlusion, static_cast<int>(scene.image.size()) / 4, random);
  const PinholeCamera fine{4 * kCamera.fx,    4 * kCamera.fy,    4 * kCamera.cx, 4 * kCamera.cy, 0,
                           4 * kCamera.width, 4 * kCamera.height};
  std::vector<ImageSegment> fine_image = scene.image;
  for (ImageSegment& segment : fine_image) {
    segment.start *= 4.0f;
    segment.end *= 4.0f;
    segment.start_covariance *= 16.0f;
    segment.end_covariance *= 16.0f;
  }
  for (int trial = 0; trial < 3; ++trial) {
    const PoseWithCovariance prior = dgpsPrior(random);
    const AcquisitionOptions options;
    const Acquisition coarse =
        acquirePose(scene.image, street.edges, occlusion, prior, kCamera, options);
    const Acquisition sharp =
        acquirePose(fine_image, street.edges, occlusion, prior, fine, options);
    EXPECT_EQ(sharp.alignment.status, coarse.alignment.status) << sharp.alignment.message;
    EXPECT_EQ(sharp.summary.hypotheses, coarse.summary.hypotheses);
    EXPECT_NEAR(sharp.summary.best_score, coarse.summary.best_score,
                1e-3 * coarse.summary.best_score);
    EXPECT_LT((sharp.alignment.T_world_camera.pose.translation() -
               coarse.alignment.T_world_camera.pose.translation())
                  .norm(),
              1e-3);
    EXPECT_NEAR(sharp.alignment.rms_residual_px, 4 * coarse.alignment.rms_residual_px,
                1e-3 * coarse.alignment.rms_residual_px);
  }
}

TEST(PoseSearch, ScoresTheTruePoseAboveOnesMetresAway) {
  const Street street = makeStreet();
  const OcclusionScene occlusion(street.faces, street.face_building_ids);
  std::mt19937 random(9);
  const Scene scene = render(street, occlusion, 10, random);
  const PoseSearchOptions options;
  const OrientedDistanceMap map(scene.image, kCamera.width, kCamera.height, {15.0, 6.0, 1});
  const Coverage truth = measureCoverage(scene.visible, truePose().pose, kCamera, map, options);
  EXPECT_GT(truth.covered_px, 0.8 * truth.model_px);
  for (const Eigen::Vector3d& offset :
       {Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(0, 5, 0), Eigen::Vector3d(-3, -3, 0)}) {
    Eigen::Isometry3d moved = truePose().pose;
    moved.translation() += offset;
    const PoseWithCovariance viewpoint{moved, Matrix6d::Zero()};
    const Coverage elsewhere =
        measureCoverage(visibleSegments(street.edges, occlusion, viewpoint, kCamera, {}), moved,
                        kCamera, map, options);
    EXPECT_LT(elsewhere.score, truth.score) << offset.transpose();
  }
}

TEST(PoseSearch, InsideABuildingThereIsNothingToFind) {
  Street block;
  addBox(block, -100, -100, 100, 100, 30);
  const OcclusionScene occlusion(block.faces, block.face_building_ids);
  const PoseSearch search(block.edges, occlusion, kCamera, PoseSearchOptions{});
  PoseWithCovariance prior = truePose();
  prior.covariance = diagonalPoseCovariance(2.0, 0.01);
  std::mt19937 random(1);
  EXPECT_TRUE(search.search(render(block, occlusion, 20, random).image, prior).empty());
}

}  // namespace
}  // namespace lineloc
