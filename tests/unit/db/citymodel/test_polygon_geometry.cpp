// The face checks and repairs the loader runs on real models: degenerate faces
// dropped, non-planar faces triangulated (or dropped when they have holes),
// each counted.
#include <gtest/gtest.h>

#include "db/citymodel/polygon_geometry.h"

namespace lineloc::citymodel {
namespace {

Face square(double bent_corner_z_m, SurfaceKind kind) {
  return Face{kind, {{{0, 0, 5}, {4, 0, 5}, {4, 4, 5}, {0, 4, 5 + bent_corner_z_m}}}};
}

TEST(PolygonGeometry, ANonPlanarFaceBecomesPlanarTrianglesOfItsKind) {
  Building building;
  building.id = "b";
  building.faces = {square(0.0, SurfaceKind::kRoof), square(0.3, SurfaceKind::kRoof)};
  const FaceValidation validation;
  EXPECT_THROW(validateFaces(building.faces, validation, "f.json", "b"), ModelError);
  SkippedObjects skipped;
  triangulateNonPlanarFaces(building, validation, "f.json", skipped);
  ASSERT_EQ(building.faces.size(), 3u) << "the planar square, and two triangles";
  EXPECT_EQ(building.faces[0].rings.front().size(), 4u);
  for (size_t index = 1; index < building.faces.size(); ++index) {
    EXPECT_EQ(building.faces[index].rings.front().size(), 3u);
    EXPECT_EQ(building.faces[index].kind, SurfaceKind::kRoof);
  }
  EXPECT_NO_THROW(validateFaces(building.faces, validation, "f.json", "b"));
  EXPECT_EQ(skipped.count_by_reason.at("non-planar face triangulated"), 1);
  ASSERT_EQ(skipped.messages.size(), 1u);
  EXPECT_NE(skipped.messages[0].find("f.json: object 'b': face 1"), std::string::npos)
      << skipped.messages[0];
}

TEST(PolygonGeometry, ABendWithinTheToleranceIsLeftAlone) {
  Building building;
  building.id = "b";
  building.faces = {square(0.04, SurfaceKind::kWall)};
  SkippedObjects skipped;
  triangulateNonPlanarFaces(building, {}, "f.json", skipped);
  EXPECT_EQ(building.faces.size(), 1u);
  EXPECT_EQ(skipped.total(), 0);
}

TEST(PolygonGeometry, ANonPlanarFaceWithAHoleIsDroppedAndCounted) {
  Building building;
  building.id = "b";
  Face holed = square(0.3, SurfaceKind::kWall);
  holed.rings.push_back({{1, 1, 5}, {1, 2, 5}, {2, 2, 5}});
  building.faces = {square(0.0, SurfaceKind::kRoof), holed};
  SkippedObjects skipped;
  triangulateNonPlanarFaces(building, {}, "f.json", skipped);
  EXPECT_EQ(building.faces.size(), 1u);
  EXPECT_EQ(skipped.count_by_reason.at("non-planar face with holes dropped"), 1);
}

}  // namespace
}  // namespace lineloc::citymodel
