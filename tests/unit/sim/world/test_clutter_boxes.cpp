#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "sim/world/city_mesh.h"
#include "sim/world/clutter_boxes.h"

namespace lineloc {
namespace {

SceneMesh streetWithACarAndAPole() {
  SceneMesh scene;
  scene.addBox(Eigen::Isometry3d(Eigen::Translation3d(0, 0, 5)), {5, 5, 5},
               SurfaceTag{SurfaceKind::kWall, 5, 0.0f, 10.0f});
  scene.addBox(Eigen::Isometry3d(Eigen::Translation3d(8, 2, 0.75)), {2.2, 0.9, 0.75},
               SurfaceTag{SurfaceKind::kCarBody, kFirstClutterObjectId, 0.0f, 1.5f});
  scene.addBox(Eigen::Isometry3d(Eigen::Translation3d(8, 2, 1.7)), {1.0, 0.8, 0.2},
               SurfaceTag{SurfaceKind::kCarWindow, kFirstClutterObjectId, 0.0f, 1.9f});
  scene.addBox(Eigen::Isometry3d(Eigen::Translation3d(12, 0, 2)), {0.05, 0.05, 2},
               SurfaceTag{SurfaceKind::kPole, kFirstClutterObjectId + 1, 0.0f, 4.0f});
  return scene;
}

TEST(ClutterBoxes, EachObjectIsTheBoxAroundItsTriangles) {
  const std::vector<ClutterBox> boxes =
      clutterBoxes(streetWithACarAndAPole(), kFirstClutterObjectId);
  ASSERT_EQ(boxes.size(), 2u);
  EXPECT_EQ(boxes[0].kind, "car");
  EXPECT_LT((boxes[0].box_world.min() - Eigen::Vector3d(5.8, 1.1, 0.0)).norm(), 1e-6);
  EXPECT_LT((boxes[0].box_world.max() - Eigen::Vector3d(10.2, 2.9, 1.9)).norm(), 1e-6);
  EXPECT_EQ(boxes[1].kind, "pole");
  EXPECT_EQ(boxes[1].object_id, kFirstClutterObjectId + 1);
}

TEST(ClutterBoxes, FileRoundTripsAndAMalformedRowIsNamed) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("clutter_" + std::to_string(getpid()) + ".txt");
  const std::vector<ClutterBox> boxes =
      clutterBoxes(streetWithACarAndAPole(), kFirstClutterObjectId);
  writeClutterBoxes(path.string(), boxes);
  const std::vector<ClutterBox> read = readClutterBoxes(path.string());
  ASSERT_EQ(read.size(), boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) {
    EXPECT_EQ(read[i].kind, boxes[i].kind);
    EXPECT_LT((read[i].box_world.min() - boxes[i].box_world.min()).norm(), 1e-4);
    EXPECT_LT((read[i].box_world.max() - boxes[i].box_world.max()).norm(), 1e-4);
  }
  for (const std::string row :
       {"1 car 0 0 0 1 1", "1 car 0 0 0 1 1 1 9", "1 car 2 0 0 1 1 1", "1 car 0 0 nan 1 1 1"}) {
    std::ofstream(path) << "1 tree 0 0 0 1 1 1\n" << row << "\n";
    try {
      readClutterBoxes(path.string());
      ADD_FAILURE() << "accepted '" << row << "'";
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(path.string() + ":2"), std::string::npos)
          << error.what();
    }
  }
  std::filesystem::remove(path);
  EXPECT_THROW(readClutterBoxes(path.string()), std::runtime_error);
}

}  // namespace
}  // namespace lineloc
