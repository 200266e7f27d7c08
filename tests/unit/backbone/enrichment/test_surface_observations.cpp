// Segments of a frame placed on the model's surface: a window's edges land on
// the wall where they are, with the side their polarity says is bright; a
// model line's segment is explained; a segment against the sky, a short one
// and one the pose cannot place precisely are left out.
#include <gtest/gtest.h>

#include "backbone/enrichment/surface_observations.h"
#include "wall_drive.h"

namespace lineloc {
namespace {

using namespace wall_drive;

class SurfaceObservationsTest : public ::testing::Test {
 protected:
  SurfaceObservationsTest() : scene_(wallFaces(), {kBuilding}) {}

  OcclusionScene scene_;
  SurfaceObservationOptions options_;
  std::mt19937 random_{7};
};

TEST_F(SurfaceObservationsTest, WindowEdgesLandOnTheWallWhereTheyAre) {
  const EnrichmentFrame frame = frameAt(cameraAt(1.0), 0.0, random_);
  const SurfaceObservations observed = observeSurfaceSegments(frame, scene_, options_);
  EXPECT_EQ(observed.explained, 1);  // the eave
  // The window's side, its frame's inner edge, its top and the post (whose
  // pixels the wall lies behind: only other views can tell).
  ASSERT_EQ(observed.segments.size(), 4u);
  const SurfaceSegment& side = observed.segments[0];
  EXPECT_EQ(side.building_id, kBuilding);
  EXPECT_NEAR(std::abs(side.plane.normal.x()), 1.0, 1e-9);
  EXPECT_NEAR(side.plane.normal.x() * kWall_x, side.plane.offset, 1e-6);
  // Pixels are floats: 1e-5 m at 10 m.
  EXPECT_LT((side.start_world - kWindowSideStart).norm(), 1e-5);
  EXPECT_LT((side.end_world - kWindowSideEnd).norm(), 1e-5);
  EXPECT_NEAR(
      side.depth_m,
      (0.5 * (kWindowSideStart + kWindowSideEnd) - frame.T_world_camera.pose.translation()).norm(),
      1e-6);
  // Placed from a pose known to 1 cm and 0.057 deg, 10 m away.
  EXPECT_GT(side.placement_sigma_m, 0.01);
  EXPECT_LT(side.placement_sigma_m, 0.02);
  // Brighter to the left of bottom -> top in the image (the camera's x axis
  // is -y): towards +y; the frame's inner edge is bright on the other side.
  EXPECT_GT(side.brighter_side.y(), 0.99);
  EXPECT_LT(observed.segments[1].brighter_side.y(), -0.99);
  EXPECT_EQ(side.view.segment.start, frame.segments[0].start);
}

TEST_F(SurfaceObservationsTest, ASkySegmentAShortOneAndAnImpreciseOneAreLeftOut) {
  EnrichmentFrame frame = frameAt(cameraAt(1.0), 0.0, random_);
  frame.segments = {
      segmentOf(frame.T_world_camera, {12.0, 2.0, 9.0}, {12.0, 4.0, 9.0}, 1, 0.0, random_),
      segmentOf(frame.T_world_camera, kWindowSideStart,
                kWindowSideStart + Eigen::Vector3d(0, 0, 0.2), 1, 0.0, random_)};
  SurfaceObservations observed = observeSurfaceSegments(frame, scene_, options_);
  EXPECT_TRUE(observed.segments.empty());
  EXPECT_EQ(observed.off_surface, 1);
  EXPECT_EQ(observed.too_short, 1);

  frame = frameAt(cameraAt(1.0), 0.0, random_);
  // A fix that leaves the position along the street open by 0.3 m places
  // the window's side (across it: along the street) imprecisely, its top
  // (across it: up) well.
  frame.T_world_camera.covariance(1, 1) = 0.3 * 0.3;
  observed = observeSurfaceSegments(frame, scene_, options_);
  ASSERT_EQ(observed.imprecise, 3);  // the two vertical edges and the post
  ASSERT_EQ(observed.segments.size(), 1u);
  EXPECT_LT((observed.segments[0].start_world - kWindowTopStart).norm(), 1e-5);
}

}  // namespace
}  // namespace lineloc
