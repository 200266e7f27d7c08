// Street furniture along a route through a grid of blocks (streets 16 m
// wide, 1 m alleys between the buildings): cables span the street from
// façade to façade at their height, every other one with a lamp; the lane
// line's dashes lie beside the route on the ground; kerbs lie a pavement's
// width from the façades; nothing is added unless asked for. Where the route
// turns, a marking may stand off its line, and a kerb where it also passes an
// alley or a junction (the façade it is laid from is farther): most may not.
#include <gtest/gtest.h>

#include <map>

#include "common/geometry/line_segments.h"
#include "sim/world/street_furniture.h"
#include "sim/world/street_route.h"
#include "tests/unit/sim/world/box_city.h"

namespace lineloc {
namespace {

class StreetFurnitureTest : public ::testing::Test {
 protected:
  StreetFurnitureTest() : map_(makeBoxCity(3, 16.0), 0.5) {
    StreetRouteOptions options;
    options.length_m = 250.0;
    route_ =
        planStreetRoute(buildStreetNetwork(map_, StreetNetworkOptions{}), map_, options).waypoints;
  }

  // A street climbing 2 % eastwards.
  static double groundHeight(const Eigen::Vector2d& xy) { return 1.0 + 0.02 * xy.x(); }

  // The vertices of each object of `kind`, by object.
  static std::map<uint32_t, std::vector<Eigen::Vector3d>> objects(const SceneMesh& mesh,
                                                                  SurfaceKind kind) {
    std::map<uint32_t, std::vector<Eigen::Vector3d>> found;
    for (size_t i = 0; i < mesh.vertices().size(); ++i) {
      if (mesh.tag(i / 3).kind == kind) {
        found[mesh.tag(i / 3).object_id].push_back(mesh.vertices()[i].cast<double>());
      }
    }
    return found;
  }

  OccupancyMap map_;
  std::vector<Eigen::Vector2d> route_;
  const std::function<double(const Eigen::Vector2d&)> ground_ = groundHeight;
};

TEST_F(StreetFurnitureTest, NothingUnlessAskedFor) {
  ASSERT_GT(route_.size(), 1u);
  SceneMesh mesh;
  const StreetFurnitureCounts counts =
      addStreetFurniture(map_, route_, ground_, StreetFurnitureOptions{}, 5000, mesh);
  EXPECT_EQ(mesh.triangleCount(), 0u);
  EXPECT_EQ(counts.cables + counts.lamps + counts.marking_dashes + counts.kerb_m, 0);
}

TEST_F(StreetFurnitureTest, CablesSpanTheStreetAtTheirHeightWithALampOnEveryOther) {
  StreetFurnitureOptions options;
  options.cables_per_100m = 4.0;
  SceneMesh mesh;
  const StreetFurnitureCounts counts =
      addStreetFurniture(map_, route_, ground_, options, 5000, mesh);
  // One every 25 m of the 250 m route where façades stand on both sides.
  EXPECT_GE(counts.cables, 6);
  EXPECT_LE(counts.cables, 10);
  EXPECT_EQ(counts.lamps, (counts.cables + 1) / 2);
  const auto pieces = objects(mesh, SurfaceKind::kCable);
  double length_m = 0.0;
  for (const auto& [id, vertices] : pieces) {
    EXPECT_GE(id, 5000u);
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& vertex : vertices) {
      box.extend(vertex);
      const double above_m = vertex.z() - groundHeight(vertex.head<2>());
      EXPECT_GT(above_m, options.min_cable_height_m - 0.2);
      EXPECT_LT(above_m, options.max_cable_height_m + 0.2);
    }
    // A piece is at most a metre long and as thin as the cable.
    EXPECT_LE(box.sizes().head<2>().norm(), 1.0 + 2.0 * options.cable_diameter_m);
    EXPECT_LE(box.sizes().z(), 2.0 * options.cable_diameter_m + 0.02);
    length_m += box.sizes().head<2>().norm();
  }
  // Each spans the street, façade to façade: 16 m, more across a junction.
  EXPECT_GE(length_m / counts.cables, 15.0);
  EXPECT_LE(length_m / counts.cables, options.max_cable_span_m);
}

TEST_F(StreetFurnitureTest, TheLaneLineAndTheKerbsLieWhereTheyBelong) {
  StreetFurnitureOptions options;
  options.lane_markings = true;
  options.kerbs = true;
  SceneMesh mesh;
  const StreetFurnitureCounts counts =
      addStreetFurniture(map_, route_, ground_, options, 5000, mesh);
  // A dash every 9 m along most of the route.
  EXPECT_GT(counts.marking_dashes, 20);
  EXPECT_LE(counts.marking_dashes, 28);
  int markings = 0;
  int markings_on_line = 0;
  for (const auto& [id, vertices] : objects(mesh, SurfaceKind::kRoadMarking)) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& vertex : vertices) {
      EXPECT_NEAR(vertex.z(), groundHeight(vertex.head<2>()), 0.02);
      centre += vertex / static_cast<double>(vertices.size());
    }
    ++markings;
    const double off_m =
        std::abs(distanceToPolyline(centre.head<2>(), route_) - options.lane_marking_offset_m);
    markings_on_line += off_m < 0.1 ? 1 : 0;
  }
  EXPECT_GE(markings_on_line, 0.9 * markings);
  // Kerbs on both sides of most of it.
  EXPECT_GT(counts.kerb_m, 250.0);
  int kerbs = 0;
  int kerbs_at_pavement = 0;
  for (const auto& [id, vertices] : objects(mesh, SurfaceKind::kKerb)) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& vertex : vertices) {
      EXPECT_GT(map_.clearanceAt(vertex.head<2>()), 0.0) << "a kerb inside a building";
      EXPECT_LT(vertex.z() - groundHeight(vertex.head<2>()), 0.15);
      centre += vertex / static_cast<double>(vertices.size());
    }
    ++kerbs;
    const double off_m = std::abs(map_.clearanceAt(centre.head<2>()) - options.pavement_width_m);
    kerbs_at_pavement += off_m < 0.3 ? 1 : 0;
  }
  EXPECT_GE(kerbs_at_pavement, 0.8 * kerbs);
}

}  // namespace
}  // namespace lineloc
