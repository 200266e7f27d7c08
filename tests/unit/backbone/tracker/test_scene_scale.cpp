#include <gtest/gtest.h>

#include <stdexcept>

#include "backbone/tracker/scene_scale.h"

namespace lineloc {
namespace {

const PinholeCamera kCamera{
    .fx = 500.0, .fy = 500.0, .cx = 320.0, .cy = 240.0, .width = 640, .height = 480};

// A camera at the origin looking along world +y (OpenCV axes: x right, y
// down, z forward).
Eigen::Isometry3d lookingNorth() {
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
  T_world_camera.linear() << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  return T_world_camera;
}

// A wall facing the camera `distance_m` ahead, wide and high enough to fill
// the view when `fills_view`, else only its middle third.
OcclusionScene wallAhead(double distance_m, bool fills_view) {
  const double half_m = fills_view ? 10.0 * distance_m : 0.2 * distance_m;
  const FaceRing face = {{-half_m, distance_m, -half_m},
                         {half_m, distance_m, -half_m},
                         {half_m, distance_m, half_m},
                         {-half_m, distance_m, half_m}};
  return OcclusionScene({face}, {0});
}

TEST(SceneScale, IsTheModelsDepthOverTheStreetsAndIgnoresRaysThatMeetNothing) {
  // Every ray meets a wall facing the camera at its distance, whatever the
  // ray's angle.
  EXPECT_NEAR(sceneMetresPerUnit(wallAhead(24.0, true), kCamera, lookingNorth(), 12.0), 2.0, 1e-6);
  EXPECT_NEAR(sceneMetresPerUnit(wallAhead(0.6, true), kCamera, lookingNorth(), 12.0), 0.05, 1e-6);
  // Sky around a small object does not count.
  EXPECT_NEAR(sceneMetresPerUnit(wallAhead(0.6, false), kCamera, lookingNorth(), 12.0), 0.05, 1e-6);
}

TEST(SceneScale, IsOneWhenTheCameraSeesNoFace) {
  Eigen::Isometry3d looking_south = lookingNorth();
  looking_south.linear() = -looking_south.linear();
  looking_south.linear().col(0) = -looking_south.linear().col(0);
  EXPECT_EQ(sceneMetresPerUnit(wallAhead(6.0, false), kCamera, looking_south, 12.0), 1.0);
}

TEST(SceneScale, RefusesAStreetDepthThatIsNotPositive) {
  EXPECT_THROW(sceneMetresPerUnit(wallAhead(6.0, true), kCamera, lookingNorth(), 0.0),
               std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
