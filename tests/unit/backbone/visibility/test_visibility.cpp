// Hidden-line removal on scenes whose visible edges follow from elementary geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "backbone/visibility/visible_corners.h"
#include "backbone/visibility/visible_lines.h"
#include "db/citymodel/line_extraction.h"

namespace lineloc {
namespace {

const PinholeCamera kCamera{500, 500, 320, 240, 0, 640, 480};

// A box [x0, x1] x [y0, y1] x [0, h]: 6 faces, 12 edges, one building whose id
// is that of its first edge.
struct Box {
  std::vector<FaceRing> faces;
  std::vector<int64_t> face_building_ids;
  std::vector<ModelSegment> edges;
};

Box makeBox(double x0, double y0, double x1, double y1, double h, int64_t first_id) {
  const Eigen::Vector3d c[8] = {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0},
                                {x0, y0, h}, {x1, y0, h}, {x1, y1, h}, {x0, y1, h}};
  Box box;
  box.faces = {{c[0], c[3], c[2], c[1]}, {c[4], c[5], c[6], c[7]}, {c[0], c[1], c[5], c[4]},
               {c[1], c[2], c[6], c[5]}, {c[2], c[3], c[7], c[6]}, {c[3], c[0], c[4], c[7]}};
  box.face_building_ids.assign(box.faces.size(), first_id);
  const int pairs[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                            {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (int i = 0; i < 12; ++i) {
    box.edges.push_back({first_id + i, 0, c[pairs[i][0]], c[pairs[i][1]]});
  }
  return box;
}

// The faces of all `boxes`, each box a building.
OcclusionScene sceneOf(const std::vector<const Box*>& boxes) {
  std::vector<FaceRing> faces;
  std::vector<int64_t> building_ids;
  for (const Box* box : boxes) {
    faces.insert(faces.end(), box->faces.begin(), box->faces.end());
    building_ids.insert(building_ids.end(), box->face_building_ids.begin(),
                        box->face_building_ids.end());
  }
  return OcclusionScene(faces, building_ids);
}

// Camera at `position` looking along +y (north), level: x_c = east, y_c = down.
PoseWithCovariance lookingNorth(const Eigen::Vector3d& position, double position_sigma_m) {
  Eigen::Matrix3d R_world_camera;
  R_world_camera << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  PoseWithCovariance pose;
  pose.pose.linear() = R_world_camera;
  pose.pose.translation() = position;
  pose.covariance = diagonalPoseCovariance(position_sigma_m, 0.01);
  return pose;
}

std::vector<int64_t> ids(const std::vector<VisibleSegment>& segments) {
  std::vector<int64_t> result;
  for (const auto& s : segments)
    result.push_back(s.model_line_id);
  std::sort(result.begin(), result.end());
  return result;
}

// Seen head-on from (5, -20, 5), below the roof: only the front wall's 4 edges
// (ids 0 bottom, 4 top, 8 and 9 verticals) have a clear line of sight; the ray
// to any point (x, y > 0, z) of another edge crosses the plane y = 0 at
// (5 + (x - 5) 20 / (20 + y), 5 + (z - 5) 20 / (20 + y)), inside the front wall.
TEST(Visibility, HeadOnCubeShowsOnlyItsFrontWall) {
  const Box cube = makeBox(0, 0, 10, 10, 10, 0);
  const OcclusionScene scene = sceneOf({&cube});
  EXPECT_EQ(scene.triangleCount(), 12u);
  const auto visible =
      visibleSegments(cube.edges, scene, lookingNorth({5, -20, 5}, 0.01), kCamera, {});
  EXPECT_EQ(ids(visible), (std::vector<int64_t>{0, 4, 8, 9}));
  for (const VisibleSegment& s : visible) {
    EXPECT_DOUBLE_EQ(s.weight, 1.0);
    EXPECT_NEAR((s.end_world - s.start_world).norm(), 10.0, 1e-9);
  }
}

// A window's top edge painted on the front wall (y = 0) of the cube: a line
// of the model there would show no edge (one face on both sides of it); a
// learnt line shows wherever it is in view, carrying its uncertainty, and is
// hidden like any other behind a face in front of it.
TEST(Visibility, ALearntLineOnAWallShowsWhereItIsInView) {
  const Box cube = makeBox(0, 0, 10, 10, 10, 0);
  const ModelSegment window_top{100, static_cast<int>(citymodel::LineKind::kOther),
                                Eigen::Vector3d(3, 0, 4), Eigen::Vector3d(6, 0, 4)};
  ModelSegment learnt = window_top;
  learnt.id = -7;
  learnt.kind = static_cast<int>(citymodel::LineKind::kLearnt);
  learnt.sigma_m = 0.02;
  const OcclusionScene scene = sceneOf({&cube});
  const PoseWithCovariance view = lookingNorth({5, -20, 5}, 0.01);
  EXPECT_TRUE(visibleSegments({window_top}, scene, view, kCamera, {}).empty());
  const std::vector<VisibleSegment> visible = visibleSegments({learnt}, scene, view, kCamera, {});
  ASSERT_EQ(visible.size(), 1u);
  EXPECT_EQ(visible[0].model_line_id, -7);
  EXPECT_EQ(visible[0].sigma_m, 0.02);
  EXPECT_EQ(visible[0].polarity, 0);
  EXPECT_NEAR((visible[0].end_world - visible[0].start_world).norm(), 3.0, 1e-9);
  // A hoarding 5 m in front of the wall hides it.
  const Box hoarding = makeBox(0, -5.2, 10, -5, 8, 50);
  EXPECT_TRUE(visibleSegments({learnt}, sceneOf({&cube, &hoarding}), view, kCamera, {}).empty());
}

// The image direction of a piece's projection, start -> end.
Eigen::Vector2d projectedDirection(const VisibleSegment& segment,
                                   const PoseWithCovariance& T_world_camera) {
  const Eigen::Isometry3d T_camera_world = T_world_camera.pose.inverse();
  return kCamera.project(T_camera_world * segment.end_world) -
         kCamera.project(T_camera_world * segment.start_world);
}

// Camera at (-15, -15, 5) looking north-east, level: at the south-west corner
// of a cube [0, 10]^3.
PoseWithCovariance diagonalView() {
  PoseWithCovariance pose = lookingNorth({-15, -15, 5}, 0.01);
  pose.pose.linear() = Eigen::AngleAxisd(-M_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                       pose.pose.linear();
  return pose;
}

// From the south-west diagonal two walls show: 7 edges.
TEST(Visibility, DiagonalViewShowsTwoWalls) {
  const Box cube = makeBox(0, 0, 10, 10, 10, 0);
  const OcclusionScene scene = sceneOf({&cube});
  const auto visible = visibleSegments(cube.edges, scene, diagonalView(), kCamera, {});
  // bottom 0 (south) and 3 (west), top 4 and 7, verticals 8 (SW), 9 (SE), 11 (NW).
  EXPECT_EQ(ids(visible), (std::vector<int64_t>{0, 3, 4, 7, 8, 9, 11}));
}

// The same view under a known sun: the south-west vertical (8) lies between
// the south wall (normal -y) and the west wall (-x). A sun in the south-west
// lights both alike (n . s equal), a sun in the north-east leaves both in the
// shade (E = ambient): no edge. A sun in the south lights only the south wall,
// E = 0.35 + 0.65 cos 40 deg = 0.85 against 0.35: an edge.
TEST(Visibility, CornerBetweenWallsTheSunLightsAlikeShowsNoEdge) {
  const Box cube = makeBox(0, 0, 10, 10, 10, 0);
  const OcclusionScene scene = sceneOf({&cube});
  const auto visibleUnder = [&](double azimuth_deg) {
    VisibilityOptions options;
    options.sunlight = Sunlight::fromAzimuthElevation(azimuth_deg, 40, 0.35);
    return ids(visibleSegments(cube.edges, scene, diagonalView(), kCamera, options));
  };
  const std::vector<int64_t> without_corner = {0, 3, 4, 7, 9, 11};
  EXPECT_EQ(visibleUnder(225), without_corner);
  EXPECT_EQ(visibleUnder(45), without_corner);
  EXPECT_EQ(visibleUnder(180), (std::vector<int64_t>{0, 3, 4, 7, 8, 9, 11}));
}

// Polarity, read along each piece's projection (+1: its left side, image y
// down, is the brighter). The top edges (4 south, 7 west) have the sky above
// them, brighter than a façade: +1 where the projection runs rightwards. The
// bottom edges have the ground below them, the silhouettes (9, 11) the sky
// above the horizon and the ground below it, and the south-west vertical (8)
// two walls, whatever the sun: none.
TEST(Visibility, PredictsThatTheSkyIsBrighterThanAFacadeAgainstIt) {
  const Box cube = makeBox(0, 0, 10, 10, 10, 0);
  const OcclusionScene scene = sceneOf({&cube});
  const auto polarities = [&](const VisibilityOptions& options) {
    std::map<int64_t, int> polarity;
    for (const VisibleSegment& s :
         visibleSegments(cube.edges, scene, diagonalView(), kCamera, options)) {
      const bool rightwards = projectedDirection(s, diagonalView()).x() > 0.0;
      polarity[s.model_line_id] = rightwards ? s.polarity : -s.polarity;
    }
    return polarity;
  };
  const std::map<int64_t, int> expected = {{0, 0}, {3, 0}, {4, 1}, {7, 1}, {8, 0}, {9, 0}, {11, 0}};
  VisibilityOptions options;
  EXPECT_EQ(polarities(options), expected);
  options.sunlight = Sunlight::fromAzimuthElevation(180, 40, 0.35);
  EXPECT_EQ(polarities(options), expected);

  options.predict_polarity = false;
  for (const auto& [id, polarity] : polarities(options)) {
    EXPECT_EQ(polarity, 0) << id;
  }
}

// The side of each piece its own façade lies on, as an image direction:
// facade_side times the left normal (image, y down) of its projection.
std::map<int64_t, Eigen::Vector2d> facadeDirections(const std::vector<VisibleSegment>& visible,
                                                    const PoseWithCovariance& T_world_camera) {
  std::map<int64_t, Eigen::Vector2d> directions;
  for (const VisibleSegment& s : visible) {
    const Eigen::Vector2d along = projectedDirection(s, T_world_camera).normalized();
    directions[s.model_line_id] = s.facade_side * Eigen::Vector2d(along.y(), -along.x());
  }
  return directions;
}

// From the south-west diagonal, the silhouettes' façades lie inwards (9, the
// south-east vertical, on the right of the image has its wall to its left; 11
// the converse), the roof lines' below them, the feet's above, whether the sky
// or a farther building lies beyond: a block [20, 26] x [-10, 12] x [0, 20]
// seen right of the south-east corner is at least 1.4 times as far (the sight
// line past the corner, (10, 0) + t (25, 15), reaches x = 20 at 41 m, the
// corner at 29 m). The south-west vertical (8) has a wall on both sides.
TEST(Visibility, KnowsWhichSideOfALineItsOwnFacadeIsOn) {
  const Box cube = makeBox(0, 0, 10, 10, 10, 0);
  const Box behind = makeBox(20, -10, 26, 12, 20, 100);
  for (const OcclusionScene& scene : {sceneOf({&cube}), sceneOf({&cube, &behind})}) {
    const auto facade = facadeDirections(
        visibleSegments(cube.edges, scene, diagonalView(), kCamera, {}), diagonalView());
    ASSERT_EQ(facade.size(), 7u);
    EXPECT_LT(facade.at(9).x(), -0.9);
    EXPECT_GT(facade.at(11).x(), 0.9);
    for (const int64_t roof : {4, 7}) {
      EXPECT_GT(facade.at(roof).y(), 0.5) << roof;
    }
    for (const int64_t foot : {0, 3}) {
      EXPECT_LT(facade.at(foot).y(), -0.5) << foot;
    }
    EXPECT_EQ(facade.at(8), Eigen::Vector2d::Zero());
  }
}

// A tower [-5, 5] x [-12, -8] x [0, 30] south of the cube, clear of the
// view of the south-west corner (the sight line crosses y = -8 at x = -8),
// shades that corner from a sun in the south at 40 degrees: the ray from
// (0, 0, z <= 10) towards it reaches y = -8 at z + 8 tan 40 deg < 17 m. Both
// walls then receive the ambient share alone, and the corner shows no edge.
TEST(Visibility, CornerInTheShadowOfAnotherBuildingShowsNoEdge) {
  const Box cube = makeBox(0, 0, 10, 10, 10, 0);
  const Box tower = makeBox(-5, -12, 5, -8, 30, 100);
  VisibilityOptions options;
  options.sunlight = Sunlight::fromAzimuthElevation(180, 40, 0.35);
  const auto corner_shows = [&](const OcclusionScene& scene) {
    const auto visible = ids(visibleSegments(cube.edges, scene, diagonalView(), kCamera, options));
    return std::find(visible.begin(), visible.end(), 8) != visible.end();
  };
  EXPECT_TRUE(corner_shows(sceneOf({&cube})));
  EXPECT_FALSE(corner_shows(sceneOf({&cube, &tower})));
}

// A low wall (height 4) in front of the cube hides the lower part of its
// front verticals: the ray from the eye at z = 5 over the wall top (y = -5,
// z = 4) reaches y = 0 at z = 5 - (1)(20/15) = 3.667 m.
TEST(Visibility, LowWallCutsTheVerticalsAtTheSightLine) {
  const Box cube = makeBox(0, 0, 10, 10, 10, 0);
  Box wall = makeBox(-20, -5.2, 30, -5, 4, 100);
  const OcclusionScene scene = sceneOf({&cube, &wall});
  const auto visible =
      visibleSegments(cube.edges, scene, lookingNorth({5, -20, 5}, 0.01), kCamera, {});
  const double sight_z = 5.0 - 1.0 * 20.0 / 15.0;
  int verticals = 0;
  for (const VisibleSegment& s : visible) {
    if (s.model_line_id == 8 || s.model_line_id == 9) {
      ++verticals;
      const double low = std::min(s.start_world.z(), s.end_world.z());
      // Samples every ~8 px: at 20 m with f = 500 that is 0.32 m along the edge.
      EXPECT_NEAR(low, sight_z, 0.35);
      EXPECT_NEAR(std::max(s.start_world.z(), s.end_world.z()), 10.0, 1e-9);
    }
    EXPECT_NE(s.model_line_id, 0) << "the bottom edge is behind the wall";
  }
  EXPECT_EQ(verticals, 2);
}

// Seen through a 1 m gap between two walls with 2 m position uncertainty,
// many sigma-point viewpoints lose sight of the line: it is kept (the nominal
// viewpoint sees it) with a weight well below 1.
TEST(Visibility, UncertainPositionLowersTheWeightOfLinesSeenThroughAGap) {
  const Box cube = makeBox(0, 0, 10, 10, 10, 0);
  const Box left = makeBox(-30, -10.2, 4.5, -10, 30, 100);
  const Box right = makeBox(5.5, -10.2, 40, -10, 30, 200);
  const OcclusionScene scene = sceneOf({&cube, &left, &right});
  std::vector<ModelSegment> front_top = {cube.edges[4]};
  const auto sure = visibleSegments(front_top, scene, lookingNorth({5, -20, 5}, 0.01), kCamera, {});
  const auto unsure =
      visibleSegments(front_top, scene, lookingNorth({5, -20, 5}, 2.0), kCamera, {});
  ASSERT_EQ(sure.size(), 1u);
  ASSERT_EQ(unsure.size(), 1u);
  EXPECT_DOUBLE_EQ(sure[0].weight, 1.0);
  EXPECT_LT(unsure[0].weight, 0.8);
  EXPECT_GT(unsure[0].weight, 0.0);
}

// A wall along y = 0 for x in [0, 10] whose footprint jogs back by `depth_m` at
// x = 10 and goes on along y = depth_m to x = 20, all 10 m high, one building;
// lines 0 and 1 are the creases at the near and the far end of the narrow wall
// between them, which faces +x.
struct Jog {
  std::vector<FaceRing> faces;
  std::vector<int64_t> face_building_ids{1, 1, 1};
  std::vector<ModelSegment> creases;
};

Jog makeJog(double depth_m) {
  const auto wall = [](double x0, double y0, double x1, double y1) {
    return FaceRing{{x0, y0, 0}, {x1, y1, 0}, {x1, y1, 10}, {x0, y0, 10}};
  };
  Jog jog;
  jog.faces = {wall(0, 0, 10, 0), wall(10, 0, 10, depth_m), wall(10, depth_m, 20, depth_m)};
  jog.creases = {{0, 1, {10, 0, 0}, {10, 0, 10}}, {1, 1, {10, depth_m, 0}, {10, depth_m, 10}}};
  return jog;
}

// From (14, -8) the 0.3 m narrow wall faces the camera and spans 9 px
// (u = 320 - 500 * 4 / 8 = 70 to 320 - 500 * 4 / 8.3 = 79): both creases are
// edges. From (6, -8) its back faces the camera: the near crease lies against
// the far wall, parallel and of the same building, so it shows no edge, and the
// far crease is behind the near wall.
TEST(Visibility, FootprintJogShowsOnlyWhileItsNarrowWallFacesTheCamera) {
  const Jog jog = makeJog(0.3);
  const OcclusionScene scene(jog.faces, jog.face_building_ids);
  EXPECT_EQ(ids(visibleSegments(jog.creases, scene, lookingNorth({14, -8, 5}, 0.01), kCamera, {})),
            (std::vector<int64_t>{0, 1}));
  EXPECT_TRUE(
      visibleSegments(jog.creases, scene, lookingNorth({6, -8, 5}, 0.01), kCamera, {}).empty());
}

// A 5 cm jog seen from 30 m spans 0.1 px, less than the contrast probe: the
// probes either side of each crease meet the two parallel walls. From 1 m it
// spans 12 px (u = 320 - 500 * 0.5 / 1 = 70 to 320 - 500 * 0.5 / 1.05 = 82) and
// both creases show.
TEST(Visibility, JogShowsOnlyWhereItIsWiderThanTheProbe) {
  const Jog jog = makeJog(0.05);
  const OcclusionScene scene(jog.faces, jog.face_building_ids);
  EXPECT_TRUE(
      visibleSegments(jog.creases, scene, lookingNorth({14, -30, 5}, 0.01), kCamera, {}).empty());
  EXPECT_EQ(
      ids(visibleSegments(jog.creases, scene, lookingNorth({10.5, -1, 5}, 0.01), kCamera, {})),
      (std::vector<int64_t>{0, 1}));
}

// Two flush façades meet at x = 10: an edge between two buildings, none
// between two faces of one building's plane.
TEST(Visibility, FlushFacadesShowAnEdgeOnlyBetweenBuildings) {
  const Jog flush = makeJog(0.0);
  const std::vector<FaceRing> faces = {flush.faces[0], flush.faces[2]};
  const std::vector<ModelSegment> joint = {flush.creases[0]};
  const PoseWithCovariance pose = lookingNorth({10, -10, 5}, 0.01);
  const OcclusionScene two_buildings(faces, {1, 2});
  EXPECT_EQ(visibleSegments(joint, two_buildings, pose, kCamera, {}).size(), 1u);
  const OcclusionScene one_building(faces, {1, 1});
  EXPECT_TRUE(visibleSegments(joint, one_building, pose, kCamera, {}).empty());
}

// Lines the model gives no faces (the scene is empty) predict no surfaces to
// compare: they stay visible.
TEST(Visibility, LinesWithoutFacesStayVisible) {
  const Box cube = makeBox(0, 0, 10, 10, 10, 0);
  const OcclusionScene empty({}, {});
  const auto visible =
      visibleSegments(cube.edges, empty, lookingNorth({5, -20, 5}, 0.01), kCamera, {});
  EXPECT_EQ(visible.size(), 12u);
}

// The corners' positions, sorted (x, then y, then z).
std::vector<Eigen::Vector3d> cornerPoints(const std::vector<VisibleCorner>& corners) {
  std::vector<Eigen::Vector3d> points;
  for (const VisibleCorner& corner : corners) {
    points.push_back(corner.p_world);
  }
  std::sort(points.begin(), points.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  return points;
}

// Head-on, the front wall's four edges run to its four vertices, where each
// meets another at a right angle.
TEST(VisibleCorners, HeadOnCubeShowsTheFrontWallsFourCorners) {
  const Box cube = makeBox(0, 0, 10, 10, 10, 0);
  const OcclusionScene scene = sceneOf({&cube});
  const auto visible =
      visibleSegments(cube.edges, scene, lookingNorth({5, -20, 5}, 0.01), kCamera, {});
  for (const VisibleSegment& s : visible) {
    EXPECT_TRUE(s.reaches_line_start && s.reaches_line_end) << s.model_line_id;
  }
  const std::vector<VisibleCorner> corners = visibleCorners(visible, {});
  EXPECT_EQ(cornerPoints(corners),
            (std::vector<Eigen::Vector3d>{{0, 0, 0}, {0, 0, 10}, {10, 0, 0}, {10, 0, 10}}));
  for (const VisibleCorner& corner : corners) {
    EXPECT_DOUBLE_EQ(corner.weight, 1.0);
  }
}

// Behind the low wall of LowWallCutsTheVerticalsAtTheSightLine the verticals
// end at the sight line and the foot is hidden: only the roof's two corners
// are in view.
TEST(VisibleCorners, AVertexBehindAFaceIsNoCorner) {
  const Box cube = makeBox(0, 0, 10, 10, 10, 0);
  Box wall = makeBox(-20, -5.2, 30, -5, 4, 100);
  const OcclusionScene scene = sceneOf({&cube, &wall});
  const auto visible =
      visibleSegments(cube.edges, scene, lookingNorth({5, -20, 5}, 0.01), kCamera, {});
  EXPECT_EQ(cornerPoints(visibleCorners(visible, {})),
            (std::vector<Eigen::Vector3d>{{0, 0, 10}, {10, 0, 10}}));
}

// From (18, -12, 5) the cube's west wall (x = 0) lies left of the image, more
// than the margin beyond it (u = 320 + 500 (x - 18) / (12 + y) < -400): the
// front wall's roof and foot lines are cut there, and no corner is at x = 0.
// Its east wall shows, and the vertices at x = 10 are corners.
TEST(VisibleCorners, AVertexOutsideTheFrustumIsNoCorner) {
  const Box cube = makeBox(0, 0, 10, 10, 10, 0);
  const OcclusionScene scene = sceneOf({&cube});
  const auto visible =
      visibleSegments(cube.edges, scene, lookingNorth({18, -12, 5}, 0.01), kCamera, {});
  const std::vector<Eigen::Vector3d> corners = cornerPoints(visibleCorners(visible, {}));
  EXPECT_EQ(corners,
            (std::vector<Eigen::Vector3d>{{10, 0, 0}, {10, 0, 10}, {10, 10, 0}, {10, 10, 10}}));
}

// Lines without faces: a roof line split in two at (5, 0, 10) runs on
// straight there, no corner; it turns down a vertical at (10, 0, 10).
TEST(VisibleCorners, ALineRunningOnIsNoCorner) {
  const std::vector<ModelSegment> lines = {{0, 0, {0, 0, 10}, {5, 0, 10}},
                                           {1, 0, {5, 0, 10}, {10, 0, 10}},
                                           {2, 0, {10, 0, 0}, {10, 0, 10}}};
  const OcclusionScene empty({}, {});
  const auto visible = visibleSegments(lines, empty, lookingNorth({5, -20, 5}, 0.01), kCamera, {});
  ASSERT_EQ(visible.size(), 3u);
  EXPECT_EQ(cornerPoints(visibleCorners(visible, {})), (std::vector<Eigen::Vector3d>{{10, 0, 10}}));
}

// A ground line ending at a corner makes it a building's foot; the weight is
// the least of the pieces meeting there. A piece cut short of its line's end
// (the vertical's top, hidden) leaves the roof line alone at (0, 0, 10).
TEST(VisibleCorners, TakesTheGroundAndTheLeastWeightOfItsLines) {
  constexpr int kGround = static_cast<int>(citymodel::LineKind::kGround);
  const std::vector<VisibleSegment> pieces = {
      {0, kGround, {0, 0, 0}, {10, 0, 0}, 0.5, 0, 0, true, false},
      {1, 0, {0, 0, 9}, {0, 0, 0}, 0.8, 0, 0, false, true},
      {2, 0, {0, 0, 10}, {10, 0, 10}, 1.0, 0, 0, true, false}};
  const std::vector<VisibleCorner> corners = visibleCorners(pieces, {});
  ASSERT_EQ(corners.size(), 1u);
  EXPECT_EQ(corners[0].p_world, Eigen::Vector3d(0, 0, 0));
  EXPECT_TRUE(corners[0].on_ground);
  EXPECT_DOUBLE_EQ(corners[0].weight, 0.5);
}

TEST(OcclusionScene, FirstSurfaceGivesThePlaneAndBuildingOfTheNearestFace) {
  const Jog jog = makeJog(2.0);
  const OcclusionScene scene(jog.faces, {7, 8, 9});
  const auto near_wall = scene.firstSurface({5, -10, 5}, Eigen::Vector3d::UnitY());
  ASSERT_TRUE(near_wall.has_value());
  EXPECT_EQ(near_wall->building_id, 7);
  EXPECT_NEAR(near_wall->distance_m, 10.0, 1e-5);
  EXPECT_NEAR(std::abs(near_wall->unit_normal.y()), 1.0, 1e-6);
  const auto side = scene.firstSurface({15, 1, 5}, -Eigen::Vector3d::UnitX());
  ASSERT_TRUE(side.has_value());
  EXPECT_EQ(side->building_id, 8);
  EXPECT_NEAR(std::abs(side->unit_normal.x()), 1.0, 1e-6);
  EXPECT_FALSE(scene.firstSurface({5, -10, 5}, -Eigen::Vector3d::UnitY()).has_value());
  EXPECT_FALSE(scene.firstSurface({5, -10, 5}, Eigen::Vector3d::UnitZ()).has_value());
}

// A box [0, 10] x [0, 10] x [0, 10] between the origins and the point
// (5, 20, 5): the paths from y < 0 cross it, those from beside it or from
// behind it do not, and an origin within the clearance of the point is clear.
TEST(OcclusionScene, PacketOfPathsCountsAsManyClearAsBlockedDoes) {
  const Box box = makeBox(0, 0, 10, 10, 10, 0);
  const OcclusionScene scene = sceneOf({&box});
  const Eigen::Vector3d point(5, 20, 5);
  const std::vector<Eigen::Vector3d> origins = {
      {5, -10, 5}, {2, -5, 3}, {-30, 20, 5}, {5, 30, 5}, {8, -1, 9}, {5, 20.01, 5}, {40, 5, 5}};
  int clear_one_by_one = 0;
  for (const Eigen::Vector3d& origin : origins) {
    clear_one_by_one += scene.blocked(origin, point, 0.05) ? 0 : 1;
  }
  EXPECT_EQ(clear_one_by_one, 4);
  EXPECT_EQ(scene.countClearPaths(origins, point, 0.05), clear_one_by_one);
  EXPECT_EQ(scene.countClearPaths(std::span(origins).first(2), point, 0.05), 0);
  EXPECT_EQ(scene.countClearPaths({}, point, 0.05), 0);
  const std::vector<Eigen::Vector3d> too_many(OcclusionScene::kMaxPacketOrigins + 1, origins[2]);
  EXPECT_THROW(scene.countClearPaths(too_many, point, 0.05), std::invalid_argument);
}

TEST(OcclusionScene, RejectsBuildingIdsThatAreNotOnePerFace) {
  const Jog jog = makeJog(1.0);
  EXPECT_THROW(OcclusionScene(jog.faces, {1, 2}), std::invalid_argument);
}

TEST(Visibility, FrustumClipping) {
  VisibilityOptions options;
  options.image_margin_px = 0.0;
  // Crosses the left image border (u = 0 at x = -cx z / fx = -6.4 m at z = 10).
  Eigen::Vector3d a(-20, 0, 10), b(0, 0, 10);
  ASSERT_TRUE(clipToFrustum(a, b, kCamera, options));
  EXPECT_NEAR(a.x(), -6.4, 1e-9);
  EXPECT_EQ(b, Eigen::Vector3d(0, 0, 10));
  // Behind the camera to in front: clipped at the near plane.
  a = {0, 0, -5};
  b = {0, 0, 5};
  ASSERT_TRUE(clipToFrustum(a, b, kCamera, options));
  EXPECT_NEAR(a.z(), options.near_m, 1e-12);
  // Entirely behind.
  a = {0, 0, -5};
  b = {1, 0, -1};
  EXPECT_FALSE(clipToFrustum(a, b, kCamera, options));
}

}  // namespace
}  // namespace lineloc
