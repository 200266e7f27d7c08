// The camera's view frustum as six world-frame half-spaces, and the segment
// test against it, on a camera whose frustum is known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "db/view_frustum.h"

namespace lineloc::db {
namespace {

// fx = fy = 100, principal point at the centre of a 200 x 100 image: the
// frustum spans x/z in [-1, 1] and y/z in [-0.5, 0.5] in the camera frame.
PinholeCamera camera() {
  return {.fx = 100.0, .fy = 100.0, .cx = 100.0, .cy = 50.0, .width = 200, .height = 100};
}

// A camera 1.5 m above the world origin looking north (world +y): camera x is
// world x (east), camera y is world -z (down), camera z is world y (north).
Eigen::Isometry3d lookingNorth() {
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
  T_world_camera.linear() << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  T_world_camera.translation() = Eigen::Vector3d(0.0, 0.0, 1.5);
  return T_world_camera;
}

TEST(ViewFrustum, SegmentsInsideOutsideAndCrossing) {
  const ViewFrustum frustum(lookingNorth(), camera(), 1.0, 50.0);
  const Eigen::Vector3d eye(0.0, 0.0, 1.5);
  // Ahead, inside.
  EXPECT_TRUE(
      frustum.meetsSegment(eye + Eigen::Vector3d(0, 10, 0), eye + Eigen::Vector3d(1, 10, 0)));
  // Behind the camera, before the near plane, beyond the far plane.
  EXPECT_FALSE(
      frustum.meetsSegment(eye + Eigen::Vector3d(-1, -5, 0), eye + Eigen::Vector3d(1, -5, 0)));
  EXPECT_FALSE(
      frustum.meetsSegment(eye + Eigen::Vector3d(0, 0.5, 0), eye + Eigen::Vector3d(0.1, 0.9, 0)));
  EXPECT_FALSE(
      frustum.meetsSegment(eye + Eigen::Vector3d(0, 51, 0), eye + Eigen::Vector3d(0, 60, 0)));
  // At depth 10 the image spans x in [-10, 10], height in [-5, 5] around the eye.
  EXPECT_FALSE(
      frustum.meetsSegment(eye + Eigen::Vector3d(10.1, 10, 0), eye + Eigen::Vector3d(20, 10, 0)));
  EXPECT_TRUE(
      frustum.meetsSegment(eye + Eigen::Vector3d(9.9, 10, 0), eye + Eigen::Vector3d(20, 10, 0)));
  EXPECT_FALSE(
      frustum.meetsSegment(eye + Eigen::Vector3d(0, 10, 5.1), eye + Eigen::Vector3d(0, 10, 9)));
  // Both ends outside (left and right of the image), the middle inside.
  EXPECT_TRUE(
      frustum.meetsSegment(eye + Eigen::Vector3d(-30, 10, 0), eye + Eigen::Vector3d(30, 10, 0)));
  // Both ends outside on different planes, the segment passing beside the
  // frustum: from left of the image at depth 2 to beyond the far plane.
  EXPECT_FALSE(
      frustum.meetsSegment(eye + Eigen::Vector3d(-2.5, 2, 0), eye + Eigen::Vector3d(-200, 60, 0)));
  // Through the eye from behind to in front: enters past the near plane.
  EXPECT_TRUE(
      frustum.meetsSegment(eye + Eigen::Vector3d(0, -10, 0), eye + Eigen::Vector3d(0, 10, 0)));
}

TEST(ViewFrustum, BoundsHoldTheEightCorners) {
  const ViewFrustum frustum(lookingNorth(), camera(), 1.0, 50.0);
  const Eigen::AlignedBox3d& bounds = frustum.boundsWorld();
  // Far plane at world y = 50: x in [-50, 50], height 1.5 +- 25.
  EXPECT_NEAR(bounds.min().x(), -50.0, 1e-9);
  EXPECT_NEAR(bounds.max().x(), 50.0, 1e-9);
  EXPECT_NEAR(bounds.min().y(), 1.0, 1e-9);
  EXPECT_NEAR(bounds.max().y(), 50.0, 1e-9);
  EXPECT_NEAR(bounds.min().z(), 1.5 - 25.0, 1e-9);
  EXPECT_NEAR(bounds.max().z(), 1.5 + 25.0, 1e-9);
}

TEST(ViewFrustum, BadInputIsRefusedByName) {
  const auto expectRefused = [](const Eigen::Isometry3d& pose, const PinholeCamera& camera,
                                double near_m, double far_m, const std::string& part) {
    try {
      const ViewFrustum frustum(pose, camera, near_m, far_m);
      FAIL() << "must be refused: " << part;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(part), std::string::npos) << error.what();
    }
  };
  Eigen::Isometry3d not_finite = lookingNorth();
  not_finite.translation().x() = std::numeric_limits<double>::quiet_NaN();
  expectRefused(not_finite, camera(), 1.0, 50.0, "pose is not finite");
  PinholeCamera no_focal = camera();
  no_focal.fx = 0.0;
  expectRefused(lookingNorth(), no_focal, 1.0, 50.0, "fx, fy > 0");
  PinholeCamera no_size = camera();
  no_size.height = 0;
  expectRefused(lookingNorth(), no_size, 1.0, 50.0, "positive image size");
  expectRefused(lookingNorth(), camera(), 0.0, 50.0, "0 < near < far");
  expectRefused(lookingNorth(), camera(), 5.0, 2.0, "0 < near < far");
}

}  // namespace
}  // namespace lineloc::db
