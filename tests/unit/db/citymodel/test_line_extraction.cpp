// Lines derived from faces: exactly a building's visible edges, with kinds and normals.
#include <gtest/gtest.h>

#include <map>

#include "db/citymodel/footprint_reader.h"
#include "db/citymodel/line_extraction.h"
#include "db/citymodel/synthetic_city.h"

namespace lineloc::citymodel {
namespace {

using Ring2 = std::vector<Eigen::Vector2d>;

std::map<LineKind, int> countKinds(const std::vector<ExtractedLine>& lines) {
  std::map<LineKind, int> counts;
  for (const ExtractedLine& line : lines) {
    ++counts[line.kind];
  }
  return counts;
}

const Ring2 kSquare = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
// An L: 6 corners, so 6 vertical, 6 ground and 6 eave lines.
const Ring2 kLShape = {{0, 0}, {20, 0}, {20, 8}, {8, 8}, {8, 20}, {0, 20}};

TEST(LineExtraction, UnitCubeHasItsTwelveEdges) {
  const std::vector<ExtractedLine> lines = extractLines(extrudeFootprint({kSquare}, 0.0, 10.0));
  ASSERT_EQ(lines.size(), 12u);
  const auto kinds = countKinds(lines);
  EXPECT_EQ(kinds.at(LineKind::kVertical), 4);
  EXPECT_EQ(kinds.at(LineKind::kGround), 4);
  EXPECT_EQ(kinds.at(LineKind::kEave), 4);
  for (const ExtractedLine& line : lines) {
    // Every cube edge is shared by two perpendicular faces, stored once with both.
    ASSERT_GE(line.face_b, 0);
    EXPECT_NEAR(line.normal_a.dot(line.normal_b), 0.0, 1e-12);
    EXPECT_NEAR((line.end - line.start).norm(), 10.0, 1e-12);
  }
}

TEST(LineExtraction, LShapedBlockHasEighteenEdges) {
  const auto kinds = countKinds(extractLines(extrudeFootprint({kLShape}, 0.0, 6.0)));
  EXPECT_EQ(kinds.at(LineKind::kVertical), 6);
  EXPECT_EQ(kinds.at(LineKind::kGround), 6);
  EXPECT_EQ(kinds.at(LineKind::kEave), 6);
  EXPECT_EQ(kinds.size(), 3u);
}

TEST(LineExtraction, TriangulatedRoofAndSplitWallLeaveNoExtraLine) {
  std::vector<Face> faces = extrudeFootprint({kSquare}, 0.0, 10.0);
  // faces[1] is the roof (10 x 10 at z = 10): replace it by two triangles.
  const auto roof = faces[1].rings[0];
  faces[1].rings[0] = {roof[0], roof[1], roof[2]};
  faces.push_back({SurfaceKind::kRoof, {{roof[0], roof[2], roof[3]}}});
  // faces[2] is the wall along y = 0: split it at x = 4 into two coplanar quads
  // (the roof and ground keep their full edges, a T-junction at x = 4).
  const auto wall = faces[2].rings[0];  // (0,0,0) (10,0,0) (10,0,10) (0,0,10)
  const Eigen::Vector3d bottom_split(4, 0, 0), top_split(4, 0, 10);
  faces[2].rings[0] = {wall[0], bottom_split, top_split, wall[3]};
  faces.push_back({SurfaceKind::kWall, {{bottom_split, wall[1], wall[2], top_split}}});

  const std::vector<ExtractedLine> lines = extractLines(faces);
  ASSERT_EQ(lines.size(), 12u);
  for (const ExtractedLine& line : lines) {
    EXPECT_NEAR((line.end - line.start).norm(), 10.0, 1e-9) << "split pieces must merge";
  }
}

TEST(LineExtraction, CourtyardHoleAddsItsInnerEdges) {
  const Ring2 hole = {{3, 3}, {7, 3}, {7, 7}, {3, 7}};
  // Outer and inner boundaries each give 4 vertical, 4 ground and 4 eave lines.
  EXPECT_EQ(extractLines(extrudeFootprint({kSquare, hole}, 0.0, 5.0)).size(), 24u);
}

TEST(LineExtraction, SyntheticCityHasTwelveLinesPerFlatAndFifteenPerGabledBuilding) {
  const CityModel city = generateSyntheticCity({.building_count = 300, .seed = 3});
  ASSERT_EQ(city.buildings.size(), 300u);
  int flat = 0, gabled = 0;
  std::map<LineKind, int> kinds;
  size_t lines = 0;
  for (const Building& building : city.buildings) {
    const bool is_gabled = building.attributes_json.find("gabled") != std::string::npos;
    (is_gabled ? gabled : flat) += 1;
    const std::vector<ExtractedLine> extracted = extractLines(building.faces);
    EXPECT_EQ(extracted.size(), is_gabled ? 15u : 12u) << building.id;
    for (const auto& [kind, count] : countKinds(extracted))
      kinds[kind] += count;
    lines += extracted.size();
  }
  EXPECT_GT(flat, 0);
  EXPECT_GT(gabled, 0);
  EXPECT_EQ(kinds[LineKind::kRidge], gabled);
  EXPECT_EQ(kinds[LineKind::kEave], 4 * flat + 2 * gabled);
  EXPECT_EQ(kinds[LineKind::kOther], 4 * gabled);  // the sloping gable rakes
  EXPECT_EQ(kinds[LineKind::kVertical], 4 * 300);
  EXPECT_EQ(kinds[LineKind::kGround], 4 * 300);
}

TEST(LineExtraction, CoplanarThresholdDecidesWhetherAShallowFoldIsALine) {
  // Two roof planes meeting at a ridge with a 5° fold (each tilted 2.5°).
  const double rise = 5.0 * std::tan(2.5 * M_PI / 180.0);
  const std::vector<Face> faces = {
      {SurfaceKind::kRoof, {{{0, 0, 0}, {10, 0, 0}, {10, 5, rise}, {0, 5, rise}}}},
      {SurfaceKind::kRoof, {{{0, 5, rise}, {10, 5, rise}, {10, 10, 0}, {0, 10, 0}}}}};
  const auto has_ridge = [&](double threshold_deg) {
    for (const ExtractedLine& line :
         extractLines(faces, {.coplanar_angle_rad = threshold_deg * M_PI / 180.0})) {
      if (line.face_b >= 0)
        return true;
    }
    return false;
  };
  EXPECT_FALSE(has_ridge(10.0));
  EXPECT_TRUE(has_ridge(4.0));
}

}  // namespace
}  // namespace lineloc::citymodel
