// The things the simulator puts in the street that the city model lacks
// (parked cars, trees, lamp posts, people), each as the axis-aligned box
// around its triangles: the ground truth that no line learnt from the images
// may come from.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sim/render/scene_mesh.h"

namespace lineloc {

struct ClutterBox {
  uint32_t object_id = 0;
  std::string kind;  // car, tree, pole, person, cable, marking or kerb
  Eigen::AlignedBox3d box_world;
};

// The boxes of the scene's objects with ids from first_object_id on.
std::vector<ClutterBox> clutterBoxes(const SceneMesh& scene, uint32_t first_object_id);

// One box per line: object_id kind x0 y0 z0 x1 y1 z1 (the box's corners, m,
// site frame), after a '#' header.
void writeClutterBoxes(const std::string& path, const std::vector<ClutterBox>& boxes);
// Parses that text; `source` names it in errors. Throws std::runtime_error
// naming the source and line of a malformed row.
std::vector<ClutterBox> parseClutterBoxes(std::string_view text, const std::string& source);
std::vector<ClutterBox> readClutterBoxes(const std::string& path);

}  // namespace lineloc
