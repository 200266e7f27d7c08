#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "common/geometry/polygon_triangulation.h"

namespace lineloc {
namespace {

double triangleArea(const std::vector<Eigen::Vector3d>& ring, const std::array<int, 3>& t) {
  return 0.5 * (ring[t[1]] - ring[t[0]]).cross(ring[t[2]] - ring[t[0]]).norm();
}

double totalArea(const std::vector<Eigen::Vector3d>& ring,
                 const std::vector<std::array<int, 3>>& triangles) {
  double area = 0.0;
  for (const auto& t : triangles)
    area += triangleArea(ring, t);
  return area;
}

TEST(PolygonTriangulation, ConvexWallSquare) {
  const std::vector<Eigen::Vector3d> wall = {{0, 0, 0}, {10, 0, 0}, {10, 0, 8}, {0, 0, 8}};
  const auto triangles = triangulatePolygon(wall);
  ASSERT_EQ(triangles.size(), 2u);
  EXPECT_NEAR(totalArea(wall, triangles), 80.0, 1e-9);
}

// An L-shaped roof (area 10x10 - 5x5 = 75) in either orientation, tilted in 3D:
// the triangles must cover exactly the L, none of them crossing the notch.
TEST(PolygonTriangulation, ConcaveLShapeInAnyOrientationAndPlane) {
  std::vector<Eigen::Vector3d> l_shape = {{0, 0, 0}, {10, 0, 0}, {10, 5, 0},
                                          {5, 5, 0}, {5, 10, 0}, {0, 10, 0}};
  const Eigen::Matrix3d tilt =
      Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix();
  for (Eigen::Vector3d& p : l_shape)
    p = tilt * p + Eigen::Vector3d(85000, 447000, 3);
  for (int reversed = 0; reversed < 2; ++reversed) {
    const auto triangles = triangulatePolygon(l_shape);
    ASSERT_EQ(triangles.size(), 4u);
    EXPECT_NEAR(totalArea(l_shape, triangles), 75.0, 1e-6);
    const Eigen::Vector3d notch =
        tilt * Eigen::Vector3d(7.5, 7.5, 0) + Eigen::Vector3d(85000, 447000, 3);
    for (const auto& t : triangles) {
      const Eigen::Vector3d centroid = (l_shape[t[0]] + l_shape[t[1]] + l_shape[t[2]]) / 3.0;
      EXPECT_GT((centroid - notch).norm(), 1.0);
    }
    std::reverse(l_shape.begin(), l_shape.end());
  }
}

TEST(PolygonTriangulation, DegenerateRingsGiveNothing) {
  EXPECT_TRUE(triangulatePolygon({}).empty());
  EXPECT_TRUE(triangulatePolygon({{0, 0, 0}, {1, 0, 0}}).empty());
  EXPECT_TRUE(triangulatePolygon({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}).empty());
  const double nan = std::nan("");
  EXPECT_TRUE(triangulatePolygon({{0, 0, 0}, {1, nan, 0}, {0, 1, 0}}).empty());
}

TEST(PolygonTriangulation, CollinearVerticesOnAnEdgeAreKept) {
  // A wall split at x = 5 along its bottom edge: 5 vertices, 3 triangles, area 80.
  const std::vector<Eigen::Vector3d> wall = {
      {0, 0, 0}, {5, 0, 0}, {10, 0, 0}, {10, 0, 8}, {0, 0, 8}};
  const auto triangles = triangulatePolygon(wall);
  ASSERT_EQ(triangles.size(), 3u);
  EXPECT_NEAR(totalArea(wall, triangles), 80.0, 1e-9);
}

}  // namespace
}  // namespace lineloc
