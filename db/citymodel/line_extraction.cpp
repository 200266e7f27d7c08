#include "db/citymodel/line_extraction.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <limits>
#include <unordered_map>

#include "db/citymodel/polygon_geometry.h"

namespace lineloc::citymodel {
namespace {

// Collinear pieces meet at an angle below this (0.6°) to be one crease.
const double kCollinearCos = std::cos(0.01);

// Welds vertices that fall in the same `snap` grid cell into one id.
class VertexWelder {
 public:
  explicit VertexWelder(double snap_m) : inverse_snap_(1.0 / snap_m) {}

  int id(const Eigen::Vector3d& point) {
    const Key key{std::llround(point.x() * inverse_snap_), std::llround(point.y() * inverse_snap_),
                  std::llround(point.z() * inverse_snap_)};
    const auto [found, inserted] = ids_.try_emplace(key, static_cast<int>(positions_.size()));
    if (inserted) {
      positions_.push_back(point);
    }
    return found->second;
  }

  const std::vector<Eigen::Vector3d>& positions() const { return positions_; }

 private:
  using Key = std::array<long long, 3>;
  struct KeyHash {
    size_t operator()(const Key& key) const {
      size_t hash = 1469598103934665603ull;
      for (long long value : key) {
        hash = (hash ^ static_cast<size_t>(value)) * 1099511628211ull;
      }
      return hash;
    }
  };

  double inverse_snap_;
  std::unordered_map<Key, int, KeyHash> ids_;
  std::vector<Eigen::Vector3d> positions_;
};

struct DirectedEdge {
  int from = 0;
  int to = 0;
  int face = 0;
};

// A face on an elementary edge and the way its ring runs along it: +1 from the
// lower vertex id to the higher.
struct EdgeSide {
  int face = 0;
  int direction = 1;
};

struct ElementaryEdge {
  int low = 0;
  int high = 0;
  std::vector<EdgeSide> sides;
};

struct KeptEdge {
  int low = 0;
  int high = 0;
  EdgeSide a;
  std::optional<EdgeSide> b;
};

// Vertex ids sorted by x, to find the vertices lying on an edge.
class VertexIndex {
 public:
  explicit VertexIndex(const std::vector<Eigen::Vector3d>& positions) : positions_(positions) {
    order_.resize(positions.size());
    for (size_t i = 0; i < order_.size(); ++i) {
      order_[i] = static_cast<int>(i);
    }
    std::sort(order_.begin(), order_.end(),
              [&](int a, int b) { return positions[a].x() < positions[b].x(); });
  }

  // Ids of vertices strictly inside segment from-to (farther than `tolerance`
  // from its ends, closer than it to the segment), ordered from `from` to `to`.
  std::vector<int> interiorVertices(int from, int to, double tolerance) const {
    const Eigen::Vector3d p = positions_[from];
    const Eigen::Vector3d direction = positions_[to] - p;
    const double length = direction.norm();
    const double x_low = std::min(p.x(), positions_[to].x()) - tolerance;
    const double x_high = std::max(p.x(), positions_[to].x()) + tolerance;
    auto it = std::lower_bound(order_.begin(), order_.end(), x_low,
                               [&](int id, double x) { return positions_[id].x() < x; });
    std::vector<std::pair<double, int>> found;
    for (; it != order_.end() && positions_[*it].x() <= x_high; ++it) {
      if (*it == from || *it == to) {
        continue;
      }
      const Eigen::Vector3d offset = positions_[*it] - p;
      const double along_m = offset.dot(direction) / length;
      if (along_m <= tolerance || along_m >= length - tolerance) {
        continue;
      }
      if ((offset - direction * (along_m / length)).norm() < tolerance) {
        found.emplace_back(along_m, *it);
      }
    }
    std::sort(found.begin(), found.end());
    std::vector<int> ids;
    for (const auto& [along_m, id] : found) {
      ids.push_back(id);
    }
    return ids;
  }

 private:
  const std::vector<Eigen::Vector3d>& positions_;
  std::vector<int> order_;
};

class LineExtractor {
 public:
  LineExtractor(const std::vector<Face>& faces, const LineExtractionOptions& options)
      : faces_(faces), options_(options), welder_(options.vertex_snap_m) {
    coplanar_cos_ = std::cos(options.coplanar_angle_rad);
    vertical_min_dz_ = std::cos(options.direction_tolerance_rad);
    horizontal_max_dz_ = std::sin(options.direction_tolerance_rad);
  }

  std::vector<ExtractedLine> run() {
    const std::vector<DirectedEdge> directed = collectEdges();
    const std::vector<ElementaryEdge> elementary = splitAndGroup(directed);
    std::vector<KeptEdge> kept;
    for (const ElementaryEdge& edge : elementary) {
      if (std::optional<KeptEdge> crease = creaseOf(edge)) {
        kept.push_back(*crease);
      }
    }
    return mergeCollinear(kept);
  }

 private:
  std::vector<DirectedEdge> collectEdges() {
    min_z_ = std::numeric_limits<double>::infinity();
    std::vector<DirectedEdge> edges;
    for (size_t face = 0; face < faces_.size(); ++face) {
      normals_.push_back(faceNormal(faces_[face]));
      for (const auto& ring : faces_[face].rings) {
        std::vector<int> ids;
        for (const Eigen::Vector3d& point : ring) {
          ids.push_back(welder_.id(point));
          min_z_ = std::min(min_z_, point.z());
        }
        for (size_t i = 0; i < ids.size(); ++i) {
          const int from = ids[i];
          const int to = ids[(i + 1) % ids.size()];
          if (from != to) {
            edges.push_back({from, to, static_cast<int>(face)});
          }
        }
      }
    }
    return edges;
  }

  std::vector<ElementaryEdge> splitAndGroup(const std::vector<DirectedEdge>& directed) const {
    const VertexIndex index(welder_.positions());
    std::unordered_map<uint64_t, size_t> slot_of;
    std::vector<ElementaryEdge> grouped;
    const auto add = [&](int from, int to, int face) {
      const int low = std::min(from, to);
      const int high = std::max(from, to);
      const uint64_t key = (static_cast<uint64_t>(low) << 32) | static_cast<uint32_t>(high);
      const auto [found, inserted] = slot_of.try_emplace(key, grouped.size());
      if (inserted) {
        grouped.push_back({low, high, {}});
      }
      auto& sides = grouped[found->second].sides;
      const bool seen = std::any_of(sides.begin(), sides.end(),
                                    [&](const EdgeSide& side) { return side.face == face; });
      if (!seen) {
        sides.push_back({face, from < to ? 1 : -1});
      }
    };
    for (const DirectedEdge& edge : directed) {
      int from = edge.from;
      for (int split :
           index.interiorVertices(edge.from, edge.to, options_.t_junction_tolerance_m)) {
        add(from, split, edge.face);
        from = split;
      }
      add(from, edge.to, edge.face);
    }
    return grouped;
  }

  // The edge with its two most differently oriented faces, or nothing when all
  // its faces are coplanar to within the threshold.
  std::optional<KeptEdge> creaseOf(const ElementaryEdge& edge) const {
    KeptEdge kept{edge.low, edge.high, edge.sides.front(), std::nullopt};
    if (edge.sides.size() == 1) {
      return kept;
    }
    const Eigen::Vector3d& normal_a = normals_[kept.a.face];
    double lowest_cos = 2.0;
    for (size_t i = 1; i < edge.sides.size(); ++i) {
      const double cos_angle = std::abs(normal_a.dot(normals_[edge.sides[i].face]));
      if (cos_angle < lowest_cos) {
        lowest_cos = cos_angle;
        kept.b = edge.sides[i];
      }
    }
    if (lowest_cos >= coplanar_cos_) {
      return std::nullopt;
    }
    return kept;
  }

  bool sameDirection(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    return (a.isZero() && b.isZero()) || a.dot(b) > coplanar_cos_;
  }

  Eigen::Vector3d normalOf(const std::optional<EdgeSide>& side) const {
    return side ? normals_[side->face] : Eigen::Vector3d::Zero();
  }

  // True when both edges lie between the same two planes.
  bool samePlanes(const KeptEdge& first, const KeptEdge& second) const {
    const Eigen::Vector3d a1 = normals_[first.a.face], b1 = normalOf(first.b);
    const Eigen::Vector3d a2 = normals_[second.a.face], b2 = normalOf(second.b);
    return (sameDirection(a1, a2) && sameDirection(b1, b2)) ||
           (sameDirection(a1, b2) && sameDirection(b1, a2));
  }

  std::vector<ExtractedLine> mergeCollinear(const std::vector<KeptEdge>& kept) const {
    const auto& positions = welder_.positions();
    std::vector<std::vector<int>> edges_at(positions.size());
    for (size_t i = 0; i < kept.size(); ++i) {
      edges_at[kept[i].low].push_back(static_cast<int>(i));
      edges_at[kept[i].high].push_back(static_cast<int>(i));
    }
    // continuation[edge][0 at low end, 1 at high end]: the edge it continues into.
    std::vector<std::array<int, 2>> continuation(kept.size(), {-1, -1});
    const auto end_of = [&](int edge, int vertex) { return kept[edge].low == vertex ? 0 : 1; };
    const auto other = [&](int edge, int vertex) {
      return kept[edge].low == vertex ? kept[edge].high : kept[edge].low;
    };
    for (size_t vertex = 0; vertex < positions.size(); ++vertex) {
      const std::vector<int>& around = edges_at[vertex];
      for (size_t i = 0; i < around.size(); ++i) {
        for (size_t j = i + 1; j < around.size(); ++j) {
          const int e1 = around[i], e2 = around[j];
          const int v = static_cast<int>(vertex);
          if (continuation[e1][end_of(e1, v)] >= 0 || continuation[e2][end_of(e2, v)] >= 0) {
            continue;
          }
          const Eigen::Vector3d u1 = (positions[other(e1, v)] - positions[v]).normalized();
          const Eigen::Vector3d u2 = (positions[other(e2, v)] - positions[v]).normalized();
          if (u1.dot(u2) < -kCollinearCos && samePlanes(kept[e1], kept[e2])) {
            continuation[e1][end_of(e1, v)] = e2;
            continuation[e2][end_of(e2, v)] = e1;
          }
        }
      }
    }
    std::vector<ExtractedLine> lines;
    std::vector<bool> used(kept.size(), false);
    const auto walk = [&](int first, int start_vertex) {
      int edge = first;
      int vertex = start_vertex;
      while (edge >= 0 && !used[edge]) {
        used[edge] = true;
        vertex = other(edge, vertex);
        edge = continuation[edge][end_of(edge, vertex)];
      }
      lines.push_back(makeLine(kept[first], positions[start_vertex], positions[vertex]));
    };
    for (size_t i = 0; i < kept.size(); ++i) {
      const int edge = static_cast<int>(i);
      if (!used[edge] && continuation[edge][0] < 0) {
        walk(edge, kept[edge].low);
      } else if (!used[edge] && continuation[edge][1] < 0) {
        walk(edge, kept[edge].high);
      }
    }
    return lines;
  }

  ExtractedLine makeLine(const KeptEdge& edge, const Eigen::Vector3d& start,
                         const Eigen::Vector3d& end) const {
    ExtractedLine line;
    line.start = start;
    line.end = end;
    line.face_a = edge.a.face;
    line.normal_a = normals_[edge.a.face];
    if (edge.b) {
      line.face_b = edge.b->face;
      line.normal_b = normals_[edge.b->face];
    }
    line.kind = classify(edge, start, end);
    return line;
  }

  // Convex when face b, entered from the edge, falls away behind face a's plane:
  // n_a . (n_b x d_b) < 0, with d_b the edge direction along face b's ring (its
  // interior lies to the left, n_b x d_b).
  bool isConvex(const KeptEdge& edge) const {
    if (!edge.b) {
      return true;
    }
    const auto& positions = welder_.positions();
    const Eigen::Vector3d direction_b =
        edge.b->direction * (positions[edge.high] - positions[edge.low]);
    const Eigen::Vector3d inward_b = normals_[edge.b->face].cross(direction_b);
    return normals_[edge.a.face].dot(inward_b) < 0.0;
  }

  LineKind classify(const KeptEdge& edge, const Eigen::Vector3d& start,
                    const Eigen::Vector3d& end) const {
    const Eigen::Vector3d direction = (end - start).normalized();
    if (std::abs(direction.z()) >= vertical_min_dz_) {
      return LineKind::kVertical;
    }
    if (std::abs(direction.z()) > horizontal_max_dz_) {
      return LineKind::kOther;
    }
    const SurfaceKind kind_a = faces_[edge.a.face].kind;
    const SurfaceKind kind_b = edge.b ? faces_[edge.b->face].kind : SurfaceKind::kOther;
    const bool at_lowest = std::max(start.z(), end.z()) - min_z_ < options_.t_junction_tolerance_m;
    if (kind_a == SurfaceKind::kGround || kind_b == SurfaceKind::kGround || at_lowest) {
      return LineKind::kGround;
    }
    const bool roof_a = kind_a == SurfaceKind::kRoof;
    const bool roof_b = kind_b == SurfaceKind::kRoof;
    if (!isConvex(edge) || !(roof_a || roof_b)) {
      return LineKind::kOther;
    }
    return roof_a && roof_b ? LineKind::kRidge : LineKind::kEave;
  }

  const std::vector<Face>& faces_;
  const LineExtractionOptions& options_;
  VertexWelder welder_;
  std::vector<Eigen::Vector3d> normals_;
  double min_z_ = 0.0;
  double coplanar_cos_ = 1.0;
  double vertical_min_dz_ = 1.0;
  double horizontal_max_dz_ = 0.0;
};

}  // namespace

std::vector<ExtractedLine> extractLines(const std::vector<Face>& faces,
                                        const LineExtractionOptions& options) {
  return LineExtractor(faces, options).run();
}

}  // namespace lineloc::citymodel
