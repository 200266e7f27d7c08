// Heights of a TIN: exact on a plane, the same as a search of every triangle
// on an irregular terrain, and none off the terrain.
#include <gtest/gtest.h>

#include <random>

#include "common/geometry/terrain_surface.h"

namespace lineloc {
namespace {

// A jittered n x n grid of spacing 7 m over z = f(x, y), each cell two triangles.
template <typename Height>
std::vector<TerrainSurface::Triangle> tin(int n, double jitter_m, Height height) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> offset(-jitter_m, jitter_m);
  std::vector<std::vector<Eigen::Vector3d>> points(n + 1);
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const bool border = i == 0 || j == 0 || i == n || j == n;
      const double x = 7.0 * i + (border ? 0.0 : offset(random));
      const double y = 7.0 * j + (border ? 0.0 : offset(random));
      points[i].emplace_back(x, y, height(x, y));
    }
  }
  std::vector<TerrainSurface::Triangle> triangles;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      triangles.push_back({points[i][j], points[i + 1][j], points[i + 1][j + 1]});
      triangles.push_back({points[i][j], points[i + 1][j + 1], points[i][j + 1]});
    }
  }
  return triangles;
}

TEST(TerrainSurface, IsExactOnAPlane) {
  const auto plane = [](double x, double y) { return 3.0 + 0.04 * x - 0.015 * y; };
  const TerrainSurface terrain(tin(12, 2.0, plane));
  std::mt19937 random(5);
  std::uniform_real_distribution<double> coordinate(0.0, 84.0);
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector2d xy(coordinate(random), coordinate(random));
    const std::optional<double> height = terrain.heightAt(xy);
    ASSERT_TRUE(height.has_value()) << xy.transpose();
    EXPECT_NEAR(*height, plane(xy.x(), xy.y()), 1e-9);
  }
  EXPECT_NEAR(*terrain.lowestHeight(), plane(0.0, 84.0), 1e-12);
}

TEST(TerrainSurface, AgreesWithASearchOfEveryTriangle) {
  const auto hills = [](double x, double y) {
    return 5.0 * std::sin(0.1 * x) * std::cos(0.07 * y);
  };
  const std::vector<TerrainSurface::Triangle> triangles = tin(15, 2.5, hills);
  const TerrainSurface terrain(triangles, 4.0);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(0.0, 105.0);
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector2d xy(coordinate(random), coordinate(random));
    std::optional<double> expected;
    for (const TerrainSurface::Triangle& t : triangles) {
      const Eigen::Matrix2d edges =
          (Eigen::Matrix2d() << (t[1] - t[0]).head<2>(), (t[2] - t[0]).head<2>()).finished();
      const Eigen::Vector2d b = edges.inverse() * (xy - t[0].head<2>());
      if (b.minCoeff() >= 0.0 && b.sum() <= 1.0) {
        expected = t[0].z() + b.x() * (t[1].z() - t[0].z()) + b.y() * (t[2].z() - t[0].z());
        break;
      }
    }
    ASSERT_TRUE(expected.has_value());
    ASSERT_TRUE(terrain.heightAt(xy).has_value()) << xy.transpose();
    EXPECT_NEAR(*terrain.heightAt(xy), *expected, 1e-9);
  }
}

TEST(TerrainSurface, AVastTerrainTakesAsFewCellsAsItsTriangles) {
  // Two triangles a million kilometres across: cells grow to keep their count
  // small instead of allocating 1e18 of them.
  const TerrainSurface terrain({{{{0, 0, 0}, {1e9, 0, 10}, {1e9, 1e9, 20}}},
                                {{{0, 0, 0}, {1e9, 1e9, 20}, {0, 1e9, 10}}}});
  ASSERT_TRUE(terrain.heightAt({5e8, 1e8}).has_value());
  EXPECT_NEAR(*terrain.heightAt({5e8, 1e8}), 6.0, 1e-6);
  EXPECT_THROW(TerrainSurface({{{{-1e308, 0, 0}, {1e308, 0, 0}, {0, 1, 0}}}}),
               std::invalid_argument);
}

TEST(TerrainSurface, NoHeightOffTheTerrain) {
  const TerrainSurface terrain(tin(4, 0.0, [](double, double) { return 1.0; }));
  EXPECT_FALSE(terrain.heightAt({-0.1, 5.0}).has_value());
  EXPECT_FALSE(terrain.heightAt({5.0, 28.1}).has_value());
  EXPECT_FALSE(terrain.heightAt({1e9, 1e9}).has_value());
  EXPECT_FALSE(terrain.heightAt({std::nan(""), 1.0}).has_value());
  EXPECT_TRUE(terrain.heightAt({28.0, 28.0}).has_value()) << "the corner is on the terrain";
  EXPECT_FALSE(TerrainSurface({}).heightAt({0, 0}).has_value());
  EXPECT_FALSE(TerrainSurface({}).lowestHeight().has_value());
  EXPECT_THROW(TerrainSurface({}, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
