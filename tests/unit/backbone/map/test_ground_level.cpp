// The ground level under a robot: the terrain's height under it where the
// view has terrain, else the median of the buildings' lowest points.
#include <gtest/gtest.h>

#include "backbone/map/ground_level.h"

namespace lineloc {
namespace {

db::ModelFaceRecord face(int64_t building_id, double lowest_z, double highest_z) {
  db::ModelFaceRecord record;
  record.building_id = building_id;
  record.ring_world = {{0, 0, lowest_z}, {1, 0, lowest_z}, {1, 0, highest_z}, {0, 0, highest_z}};
  return record;
}

// The plane z = 2 + 0.05 x - 0.02 y over [0, 40] x [0, 40], as two triangles.
MapView slopingTerrain() {
  const auto corner = [](double x, double y) {
    return Eigen::Vector3d(x, y, 2.0 + 0.05 * x - 0.02 * y);
  };
  MapView view;
  view.terrain = {{1, {corner(0, 0), corner(40, 0), corner(40, 40)}},
                  {2, {corner(0, 0), corner(40, 40), corner(0, 40)}}};
  view.faces = {face(1, 0.2, 10), face(2, 0.4, 8), face(3, 0.3, 9)};
  return view;
}

TEST(GroundLevel, IsTheMedianOfTheBuildingsLowestPoints) {
  MapView view;
  view.faces = {face(1, 0.2, 10), face(1, 3.0, 10), face(2, 0.4, 8), face(3, 7.5, 20),
                face(4, 0.3, 9)};
  // Lowest per building: 0.2, 0.4, 7.5 (a podium), 0.3.
  const GroundLevel ground(view);
  ASSERT_TRUE(ground.at({0, 0}).has_value());
  EXPECT_DOUBLE_EQ(*ground.at({0, 0}), 0.4);
  EXPECT_DOUBLE_EQ(*ground.at({500, -3}), 0.4);
}

TEST(GroundLevel, FollowsTheTerrainWhereItHasOne) {
  const GroundLevel ground(slopingTerrain());
  for (const Eigen::Vector2d& position : {Eigen::Vector2d(5, 30), Eigen::Vector2d(33, 7),
                                          Eigen::Vector2d(20, 20), Eigen::Vector2d(40, 0)}) {
    ASSERT_TRUE(ground.at(position).has_value());
    EXPECT_NEAR(*ground.at(position), 2.0 + 0.05 * position.x() - 0.02 * position.y(), 1e-12)
        << position.transpose();
  }
  ASSERT_TRUE(ground.at({41, 20}).has_value());
  EXPECT_DOUBLE_EQ(*ground.at({41, 20}), 0.3) << "beyond the terrain: the buildings' feet";
}

TEST(GroundLevel, NoFacesNoGround) {
  EXPECT_FALSE(GroundLevel(MapView{}).at({0, 0}).has_value());
  MapView empty_rings;
  empty_rings.faces.push_back(db::ModelFaceRecord{});
  EXPECT_FALSE(GroundLevel(empty_rings).at({0, 0}).has_value());
}

}  // namespace
}  // namespace lineloc
