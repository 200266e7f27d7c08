#include "backbone/visibility/visible_corners.h"

#include <algorithm>
#include <cmath>

#include "db/citymodel/line_extraction.h"

namespace lineloc {
namespace {

// A visible piece's end at its model line's vertex, with the piece's unit
// direction away from it.
struct VertexEnd {
  Eigen::Vector3d p_world;
  Eigen::Vector3d direction;
  double weight;
  bool ground;
  int piece;
};

std::vector<VertexEnd> vertexEnds(const std::vector<VisibleSegment>& visible) {
  std::vector<VertexEnd> ends;
  for (size_t i = 0; i < visible.size(); ++i) {
    const VisibleSegment& piece = visible[i];
    const Eigen::Vector3d direction = (piece.end_world - piece.start_world).normalized();
    const bool ground = piece.kind == static_cast<int>(citymodel::LineKind::kGround);
    const int index = static_cast<int>(i);
    if (piece.reaches_line_start) {
      ends.push_back({piece.start_world, direction, piece.weight, ground, index});
    }
    if (piece.reaches_line_end) {
      ends.push_back({piece.end_world, -direction, piece.weight, ground, index});
    }
  }
  return ends;
}

}  // namespace

std::vector<VisibleCorner> visibleCorners(const std::vector<VisibleSegment>& visible,
                                          const CornerOptions& options) {
  std::vector<VertexEnd> ends = vertexEnds(visible);
  // Sorted along x, the ends of one vertex lie within the tolerance of each
  // other there, so each vertex's partners are a short run after it.
  std::sort(ends.begin(), ends.end(),
            [](const VertexEnd& a, const VertexEnd& b) { return a.p_world.x() < b.p_world.x(); });
  const double max_cos = std::cos(options.min_corner_angle_rad);
  std::vector<bool> taken(ends.size(), false);
  std::vector<VisibleCorner> corners;
  for (size_t i = 0; i < ends.size(); ++i) {
    if (taken[i]) {
      continue;
    }
    VisibleCorner corner{ends[i].p_world, ends[i].weight, ends[i].ground, {ends[i].piece}};
    std::vector<Eigen::Vector3d> directions = {ends[i].direction};
    bool at_an_angle = false;
    for (size_t j = i + 1;
         j < ends.size() && ends[j].p_world.x() - ends[i].p_world.x() <= options.vertex_tolerance_m;
         ++j) {
      if (taken[j] || (ends[j].p_world - ends[i].p_world).norm() > options.vertex_tolerance_m) {
        continue;
      }
      taken[j] = true;
      for (const Eigen::Vector3d& direction : directions) {
        at_an_angle = at_an_angle || std::abs(ends[j].direction.dot(direction)) < max_cos;
      }
      directions.push_back(ends[j].direction);
      corner.weight = std::min(corner.weight, ends[j].weight);
      corner.on_ground = corner.on_ground || ends[j].ground;
      corner.pieces.push_back(ends[j].piece);
    }
    if (at_an_angle) {
      corners.push_back(corner);
    }
  }
  return corners;
}

}  // namespace lineloc
