#include <gtest/gtest.h>

#include "common/camera/camera_frustum.h"

namespace lineloc {
namespace {

PinholeCamera testCamera() {
  PinholeCamera camera;
  camera.fx = camera.fy = 500.0;
  camera.cx = 320.0;
  camera.cy = 240.0;
  camera.width = 640;
  camera.height = 480;
  return camera;
}

TEST(CameraFrustum, ClipsASegmentCrossingTheNearPlaneAndASide) {
  const HalfSpaces frustum = cameraFrustum(testCamera(), 1.0, 100.0);
  // Along the optical axis from z = 0 to z = 10: enters at the near plane, s = 0.1.
  const auto axis = clipSegment(frustum, {0, 0, 0}, {0, 0, 10});
  ASSERT_TRUE(axis.has_value());
  EXPECT_NEAR((*axis)[0], 0.1, 1e-12);
  EXPECT_NEAR((*axis)[1], 1.0, 1e-12);
  // At depth 10 the right edge u = 640 is at x = 320 / 500 * 10 = 6.4 m.
  const auto across = clipSegment(frustum, {0, 0, 10}, {12.8, 0, 10});
  ASSERT_TRUE(across.has_value());
  EXPECT_NEAR((*across)[1], 0.5, 1e-12);
}

TEST(CameraFrustum, RefusesSegmentsOutsideAndBehind) {
  const HalfSpaces frustum = cameraFrustum(testCamera(), 1.0, 100.0);
  EXPECT_FALSE(clipSegment(frustum, {0, 0, -5}, {0, 0, -1}).has_value());
  EXPECT_FALSE(clipSegment(frustum, {20, 0, 10}, {20, 5, 10}).has_value());
  EXPECT_FALSE(clipSegment(frustum, {0, 0, 150}, {0, 0, 200}).has_value());
}

TEST(CameraFrustum, MarginGrowsTheImage) {
  // x = 6.6 m at depth 10 is u = 650: outside the image, inside a 20 px margin.
  EXPECT_FALSE(clipSegment(cameraFrustum(testCamera(), 1.0, 100.0), {6.6, 0, 10}, {6.6, 1, 10}));
  EXPECT_TRUE(
      clipSegment(cameraFrustum(testCamera(), 1.0, 100.0, 20.0), {6.6, 0, 10}, {6.6, 1, 10}));
}

}  // namespace
}  // namespace lineloc
