#include "sim/world/clutter_boxes.h"

#include <fmt/format.h>

#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "common/text/data_rows.h"

namespace lineloc {
namespace {

const char* kindName(SurfaceKind kind) {
  switch (kind) {
    case SurfaceKind::kCarBody:
    case SurfaceKind::kCarWindow:
      return "car";
    case SurfaceKind::kTreeTrunk:
    case SurfaceKind::kFoliage:
      return "tree";
    case SurfaceKind::kPole:
      return "pole";
    case SurfaceKind::kPerson:
      return "person";
    case SurfaceKind::kCable:
      return "cable";
    case SurfaceKind::kRoadMarking:
      return "marking";
    case SurfaceKind::kKerb:
      return "kerb";
    case SurfaceKind::kWall:
    case SurfaceKind::kRoof:
    case SurfaceKind::kGround:
      break;
  }
  return "other";
}

}  // namespace

std::vector<ClutterBox> clutterBoxes(const SceneMesh& scene, uint32_t first_object_id) {
  std::map<uint32_t, ClutterBox> boxes;
  for (size_t triangle = 0; triangle < scene.triangleCount(); ++triangle) {
    const SurfaceTag& tag = scene.tag(triangle);
    if (tag.object_id < first_object_id) {
      continue;
    }
    ClutterBox& box = boxes[tag.object_id];
    box.object_id = tag.object_id;
    box.kind = kindName(tag.kind);
    for (size_t corner = 0; corner < 3; ++corner) {
      box.box_world.extend(scene.vertices()[3 * triangle + corner].cast<double>());
    }
  }
  std::vector<ClutterBox> list;
  for (auto& [id, box] : boxes) {
    list.push_back(std::move(box));
  }
  return list;
}

void writeClutterBoxes(const std::string& path, const std::vector<ClutterBox>& boxes) {
  std::ofstream out(path);
  if (!out) {
    throw std::runtime_error(fmt::format("cannot write clutter boxes to {}", path));
  }
  out << "# object_id kind x0 y0 z0 x1 y1 z1 (m, site frame): what stands in the street that "
         "the model lacks\n";
  for (const ClutterBox& box : boxes) {
    const Eigen::Vector3d& low = box.box_world.min();
    const Eigen::Vector3d& high = box.box_world.max();
    out << fmt::format("{} {} {:.4f} {:.4f} {:.4f} {:.4f} {:.4f} {:.4f}\n", box.object_id, box.kind,
                       low.x(), low.y(), low.z(), high.x(), high.y(), high.z());
  }
}

std::vector<ClutterBox> parseClutterBoxes(std::string_view text, const std::string& source) {
  std::vector<ClutterBox> boxes;
  forEachDataRow(text, [&](const std::string& line, int number) {
    std::istringstream fields(line);
    ClutterBox box;
    Eigen::Vector3d low, high;
    std::string rest;
    if (!(fields >> box.object_id >> box.kind >> low.x() >> low.y() >> low.z() >> high.x() >>
          high.y() >> high.z()) ||
        (fields >> rest) || !low.allFinite() || !high.allFinite() ||
        !(low.array() <= high.array()).all()) {
      throw std::runtime_error(fmt::format(
          "{}:{}: expected 'object_id kind x0 y0 z0 x1 y1 z1' (finite numbers, x0 <= x1 ...), "
          "got '{}'",
          source, number, line));
    }
    box.box_world = Eigen::AlignedBox3d(low, high);
    boxes.push_back(std::move(box));
  });
  return boxes;
}

std::vector<ClutterBox> readClutterBoxes(const std::string& path) {
  return parseClutterBoxes(readTextFile(path, "clutter boxes"), path);
}

}  // namespace lineloc
