// The ground level under a robot: the median of the buildings' lowest points.
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

TEST(GroundLevel, IsTheMedianOfTheBuildingsLowestPoints) {
  MapView view;
  view.faces = {face(1, 0.2, 10), face(1, 3.0, 10), face(2, 0.4, 8), face(3, 7.5, 20),
                face(4, 0.3, 9)};
  // Lowest per building: 0.2, 0.4, 7.5 (a podium), 0.3.
  ASSERT_TRUE(groundLevel(view).has_value());
  EXPECT_DOUBLE_EQ(*groundLevel(view), 0.4);
}

TEST(GroundLevel, NoFacesNoGround) {
  EXPECT_FALSE(groundLevel(MapView{}).has_value());
  MapView empty_rings;
  empty_rings.faces.push_back(db::ModelFaceRecord{});
  EXPECT_FALSE(groundLevel(empty_rings).has_value());
}

}  // namespace
}  // namespace lineloc
