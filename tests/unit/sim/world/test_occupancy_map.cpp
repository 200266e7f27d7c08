#include <gtest/gtest.h>

#include "sim/world/occupancy_map.h"
#include "tests/unit/sim/world/box_city.h"

namespace lineloc {
namespace {

TEST(OccupancyMap, ClearanceIsTheDistanceToTheNearestFacade) {
  // Two blocks 12 m apart: building faces at x = 39.5 and x = 52.5.
  const OccupancyMap map(makeBoxCity(2, 12.0), 0.25);
  // Rasterisation puts each façade within one cell (0.25 m) of its true place,
  // the distance transform is exact on the grid: tolerance 2 cells.
  EXPECT_NEAR(map.clearanceAt({46.0, 20.0}), 6.5, 0.5);
  EXPECT_NEAR(map.clearanceAt({41.5, 20.0}), 2.0, 0.5);
  EXPECT_EQ(map.clearanceAt({10.0, 10.0}), 0.0);  // inside a building
  EXPECT_GT(map.awayFromBuildings({41.5, 20.0}).x(), 0.9);
  EXPECT_LT(map.awayFromBuildings({50.5, 20.0}).x(), -0.9);
}

TEST(OccupancyMap, GridCoversTheBuildingsWithTheMargin) {
  const OccupancyMap map(makeBoxCity(1, 10.0), 0.5, 10.0);
  EXPECT_NEAR(map.buildingBounds().min().x(), 0.5, 1e-6);
  EXPECT_NEAR(map.buildingBounds().max().x(), 39.5, 1e-6);
  EXPECT_GE(map.cols() * map.cellSize(), 39.0 + 20.0);
  const cv::Point cell = map.cellOf({12.3, 7.9});
  EXPECT_LE((map.centreOf(cell) - Eigen::Vector2d(12.3, 7.9)).norm(), 0.5 * std::sqrt(2.0) * 0.5);
}

TEST(OccupancyMap, RejectsAMeshWithoutBuildings) {
  SceneMesh clutter_only;
  clutter_only.addBox(Eigen::Isometry3d::Identity(), Eigen::Vector3d::Ones(),
                      SurfaceTag{SurfaceKind::kCarBody, 1, 0.0f, 1.0f});
  EXPECT_THROW(OccupancyMap{clutter_only}, std::invalid_argument);
  EXPECT_THROW(OccupancyMap(makeBoxCity(1, 10.0), 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
