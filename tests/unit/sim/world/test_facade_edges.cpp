#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "sim/render/facade_layout.h"
#include "sim/world/facade_edges.h"

namespace lineloc {
namespace {

// One box building, 10 x 6 m, 12 m high from z = 1: four walls of two
// triangles each, counter-clockwise seen from outside.
CityMesh oneBuilding() {
  CityMesh city;
  const double x0 = 20.0, y0 = 30.0, x1 = 30.0, y1 = 36.0, z0 = 1.0, z1 = 13.0;
  const std::vector<std::array<Eigen::Vector2d, 2>> bottoms = {{{{x0, y0}, {x1, y0}}},
                                                               {{{x1, y0}, {x1, y1}}},
                                                               {{{x1, y1}, {x0, y1}}},
                                                               {{{x0, y1}, {x0, y0}}}};
  for (const auto& [a, b] : bottoms) {
    const Eigen::Vector3d p0(a.x(), a.y(), z0), p1(b.x(), b.y(), z0), p2(b.x(), b.y(), z1),
        p3(a.x(), a.y(), z1);
    CityWall wall{5, static_cast<float>(z0), static_cast<float>(z1), {}};
    wall.triangles = {{p0, p1, p2}, {p0, p2, p3}};
    city.walls.push_back(wall);
  }
  return city;
}

Eigen::Vector3d wallNormal(const CityWall& wall) {
  const auto& triangle = wall.triangles.front();
  return (triangle[1] - triangle[0]).cross(triangle[2] - triangle[0]).normalized();
}

TEST(FacadeEdges, EachEdgeLiesOnAWallWhereThePaintSteps) {
  const CityMesh city = oneBuilding();
  const std::vector<FacadeEdge> edges = facadeDetailEdges(city, {{25.0, 20.0}});
  ASSERT_GT(edges.size(), 100u);
  std::array<int, 4> per_wall{};
  for (const FacadeEdge& edge : edges) {
    EXPECT_EQ(edge.object_id, 5u);
    int on = -1;
    for (int w = 0; w < 4; ++w) {
      const CityWall& wall = city.walls[static_cast<size_t>(w)];
      const Eigen::Vector3d n = wallNormal(wall);
      if (std::abs(n.dot(edge.start - wall.triangles.front()[0])) < 1e-6 &&
          std::abs(n.dot(edge.end - wall.triangles.front()[0])) < 1e-6) {
        on = w;
      }
    }
    ASSERT_GE(on, 0) << "an edge off every wall: " << edge.start.transpose();
    ++per_wall[static_cast<size_t>(on)];
    const CityWall& wall = city.walls[static_cast<size_t>(on)];
    const Eigen::Vector3d normal = wallNormal(wall);
    const Eigen::Vector3d middle = 0.5 * (edge.start + edge.end);
    EXPECT_GE(middle.z(), 1.0 - 1e-9);
    EXPECT_LE(middle.z(), 13.0 + 1e-9);
    const Eigen::Vector3d across = (edge.end - edge.start).cross(normal).normalized() * 0.004;
    const FacadeLayout layout(wall.object_id, wall.base_z, wall.top_z);
    const auto paint = [&](const Eigen::Vector3d& point) {
      const Eigen::Vector3f p = point.cast<float>();
      return layout.at(FacadeLayout::wallU(p, normal.cast<float>()), p.z() - wall.base_z).albedo;
    };
    EXPECT_GE(std::abs(paint(middle + across) - paint(middle - across)), 0.05)
        << "no step across the edge at " << middle.transpose();
  }
  for (int count : per_wall) {
    EXPECT_GT(count, 10);
  }
}

TEST(FacadeEdges, AWallsFootIsWhereItMeetsTheGround) {
  CityMesh city = oneBuilding();
  city.ground_z_m = 1.5;  // above the model's base at 1 m
  std::array<int, 4> feet{};
  for (const FacadeEdge& edge : facadeDetailEdges(city, {{25.0, 20.0}})) {
    if (std::abs(edge.start.z() - 1.5) > 1e-9 || std::abs(edge.end.z() - 1.5) > 1e-9) {
      continue;
    }
    for (size_t w = 0; w < 4; ++w) {
      const CityWall& wall = city.walls[w];
      const Eigen::Vector3d n = wallNormal(wall);
      if (std::abs(n.dot(edge.start - wall.triangles.front()[0])) < 1e-6 &&
          std::abs(n.dot(edge.end - wall.triangles.front()[0])) < 1e-6) {
        ++feet[w];
        // One straight run along the wall, to within a sample of its corners.
        const double length = (wall.triangles.front()[1] - wall.triangles.front()[0]).norm();
        EXPECT_GT((edge.end - edge.start).norm(), length - 0.5);
      }
    }
  }
  for (const int count : feet) {
    EXPECT_EQ(count, 1);
  }
}

TEST(FacadeEdges, WallsFarFromTheDriveAreLeftOut) {
  EXPECT_TRUE(facadeDetailEdges(oneBuilding(), {{25.0, 500.0}}).empty());
  EXPECT_TRUE(facadeDetailEdges(oneBuilding(), {}).empty());
}

TEST(FacadeEdges, FileRoundTripsAndAMalformedRowIsNamed) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("facade_edges_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "facade_edges.txt").string();
  const std::vector<FacadeEdge> edges = facadeDetailEdges(oneBuilding(), {{25.0, 20.0}});
  writeFacadeEdges(path, edges);
  const std::vector<FacadeEdge> read = readFacadeEdges(path);
  ASSERT_EQ(read.size(), edges.size());
  for (size_t i = 0; i < edges.size(); ++i) {
    EXPECT_EQ(read[i].object_id, edges[i].object_id);
    EXPECT_LT((read[i].start - edges[i].start).norm(), 1e-4);
    EXPECT_LT((read[i].end - edges[i].end).norm(), 1e-4);
  }
  for (const std::string row :
       {"5 1 2 3 4 5", "5 1 2 3 4 5 6 7", "5 1 2 nan 4 5 6", "x 1 2 3 4 5 6"}) {
    std::ofstream(path) << "# header\n5 0 0 0 1 1 1\n" << row << "\n";
    try {
      readFacadeEdges(path);
      ADD_FAILURE() << "accepted '" << row << "'";
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(path + ":3"), std::string::npos) << error.what();
    }
  }
  EXPECT_THROW(readFacadeEdges((dir / "absent.txt").string()), std::runtime_error);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace lineloc
