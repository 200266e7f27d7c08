#include "sim/world/facade_edges.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "common/geometry/line_segments.h"
#include "common/text/data_rows.h"
#include "sim/render/facade_layout.h"

namespace lineloc {
namespace {

using Polygon2d = std::vector<Eigen::Vector2d>;

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

bool inside(const Polygon2d& polygon, const Eigen::Vector2d& point) {
  bool in = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > point.y()) != (b.y() > point.y()) &&
        point.x() < (b.x() - a.x()) * (point.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      in = !in;
    }
  }
  return in;
}

// The parameter intervals [t0, t1] of from + t (to - from), t in [0, 1], that
// lie inside the polygon.
std::vector<std::array<double, 2>> clipToPolygon(const Polygon2d& polygon,
                                                 const Eigen::Vector2d& from,
                                                 const Eigen::Vector2d& to) {
  const Eigen::Vector2d direction = to - from;
  std::vector<double> cuts{0.0, 1.0};
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d edge = polygon[i] - polygon[j];
    const double denominator = cross2(direction, edge);
    if (std::abs(denominator) < 1e-12) {
      continue;
    }
    const Eigen::Vector2d offset = polygon[j] - from;
    const double t = cross2(offset, edge) / denominator;
    const double s = cross2(offset, direction) / denominator;
    if (t > 0.0 && t < 1.0 && s >= 0.0 && s <= 1.0) {
      cuts.push_back(t);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<std::array<double, 2>> intervals;
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    if (cuts[k + 1] - cuts[k] > 1e-9 &&
        inside(polygon, from + 0.5 * (cuts[k] + cuts[k + 1]) * direction)) {
      intervals.push_back({cuts[k], cuts[k + 1]});
    }
  }
  return intervals;
}

bool nearAny(const CityWall& wall, const std::vector<Eigen::Vector2d>& near,
             double max_distance_m) {
  for (const auto& triangle : wall.triangles) {
    for (int i = 0, j = 2; i < 3; j = i++) {
      for (const Eigen::Vector2d& point : near) {
        if (distanceToSegment<2>(point, triangle[i].head<2>(), triangle[j].head<2>()) <=
            max_distance_m) {
          return true;
        }
      }
    }
  }
  return false;
}

// A wall triangle's coordinates (see the header) and the way back to the
// scene.
class WallFrame {
 public:
  WallFrame(const CityWall& wall, const Eigen::Vector3d& normal, const Eigen::Vector3d& on_plane)
      : normal_(normal),
        horizontal_(normal.head<2>().norm()),
        tangent_(-normal.y() / horizontal_, normal.x() / horizontal_, 0.0),
        outward_(normal.x() / horizontal_, normal.y() / horizontal_, 0.0),
        offset_(normal.dot(on_plane)),
        base_z_(wall.base_z) {}

  Eigen::Vector2d uv(const Eigen::Vector3d& point) const {
    return {tangent_.dot(point), point.z() - base_z_};
  }

  Eigen::Vector3d point(const Eigen::Vector2d& uv) const {
    const double z = base_z_ + uv.y();
    const double s = (offset_ - normal_.z() * z) / horizontal_;
    return uv.x() * tangent_ + s * outward_ + z * Eigen::Vector3d::UnitZ();
  }

 private:
  Eigen::Vector3d normal_;
  double horizontal_;
  Eigen::Vector3d tangent_;
  Eigen::Vector3d outward_;
  double offset_;
  double base_z_;
};

// Walls steeper than this (|n_z| at most 0.9) get façade detail in the export.
constexpr double kMinWallHorizontal = 0.1;

// Where the wall meets the rendered ground (terrain or plane): sampled every
// kFootSpacing_m along the wall where the wall is there, straight runs merged
// while every sample stays within kFootStraightness_m of the run's chord.
constexpr double kFootSpacing_m = 0.25;
constexpr double kFootStraightness_m = 0.01;

void addWallFoot(const CityWall& wall, const CityMesh& city, std::vector<FacadeEdge>& edges) {
  // The wall's frame is its first triangle's; its triangles are coplanar but
  // for a model's small warps.
  const auto& first = wall.triangles.front();
  const Eigen::Vector3d normal = (first[1] - first[0]).cross(first[2] - first[0]).normalized();
  if (!normal.allFinite() || normal.head<2>().norm() < kMinWallHorizontal) {
    return;
  }
  const WallFrame frame(wall, normal, first[0]);
  std::vector<Polygon2d> polygons;
  double u_min = std::numeric_limits<double>::infinity(), u_max = -u_min;
  for (const auto& triangle : wall.triangles) {
    Polygon2d& polygon = polygons.emplace_back();
    for (const Eigen::Vector3d& point : triangle) {
      polygon.push_back(frame.uv(point));
      u_min = std::min(u_min, polygon.back().x());
      u_max = std::max(u_max, polygon.back().x());
    }
  }
  const auto on_wall = [&](const Eigen::Vector2d& uv) {
    return std::any_of(polygons.begin(), polygons.end(),
                       [&](const Polygon2d& polygon) { return inside(polygon, uv); });
  };
  std::vector<Eigen::Vector3d> run;
  const auto flush = [&] {
    if (run.size() >= 2 && (run.back() - run.front()).norm() >= kFootSpacing_m) {
      edges.push_back({wall.object_id, run.front(), run.back()});
    }
    run.clear();
  };
  const auto straight = [&](const Eigen::Vector3d& next) {
    const Eigen::Vector3d chord = (next - run.front()).normalized();
    return std::all_of(run.begin(), run.end(), [&](const Eigen::Vector3d& point) {
      const Eigen::Vector3d offset = point - run.front();
      return (offset - offset.dot(chord) * chord).norm() <= kFootStraightness_m;
    });
  };
  for (double u = u_min; u <= u_max; u += kFootSpacing_m) {
    const Eigen::Vector3d at_base = frame.point({u, 0.0});
    const double ground_v = groundHeightAt(city, at_base.head<2>()) - wall.base_z;
    // Just above the ground: the wall must stand there.
    if (!on_wall({u, ground_v + 0.5 * kFootSpacing_m})) {
      flush();
      continue;
    }
    const Eigen::Vector3d foot = frame.point({u, ground_v});
    if (run.size() >= 2 && !straight(foot)) {
      const Eigen::Vector3d last = run.back();
      flush();
      run.push_back(last);
    }
    run.push_back(foot);
  }
  flush();
}

// The edges on one of the wall's triangles, laid out along its own normal as
// the shader lays them.
void addTriangleEdges(const CityWall& wall, const std::array<Eigen::Vector3d, 3>& triangle,
                      const FacadeEdgeOptions& options, std::vector<FacadeEdge>& edges) {
  const Eigen::Vector3d cross = (triangle[1] - triangle[0]).cross(triangle[2] - triangle[0]);
  if (!(cross.norm() > 0.0)) {
    return;  // no area: not rendered
  }
  const Eigen::Vector3d normal = cross.normalized();
  if (normal.head<2>().norm() < kMinWallHorizontal) {
    return;
  }
  const WallFrame frame(wall, normal, triangle[0]);
  Polygon2d polygon;
  double u_min = std::numeric_limits<double>::infinity(), u_max = -u_min, v_max = -u_min;
  for (const Eigen::Vector3d& point : triangle) {
    polygon.push_back(frame.uv(point));
    u_min = std::min(u_min, polygon.back().x());
    u_max = std::max(u_max, polygon.back().x());
    v_max = std::max(v_max, polygon.back().y());
  }
  const FacadeLayout layout(wall.object_id, wall.base_z, wall.top_z);
  const auto paint = [&](const Eigen::Vector2d& uv) {
    return layout.at(static_cast<float>(uv.x()), static_cast<float>(uv.y())).albedo;
  };
  const double spacing = options.sample_spacing_m;
  for (const WallBorder& border : layout.borders(u_min, u_max, v_max)) {
    const Eigen::Vector2d along = border.to_uv - border.from_uv;
    const double length = along.norm();
    if (length < spacing) {
      continue;
    }
    const Eigen::Vector2d across = Eigen::Vector2d(-along.y(), along.x()) / length * 0.5 * spacing;
    for (const auto& [t0, t1] : clipToPolygon(polygon, border.from_uv, border.to_uv)) {
      const int samples = std::max(1, static_cast<int>((t1 - t0) * length / spacing));
      int run_start = -1;
      for (int k = 0; k <= samples; ++k) {
        bool step = false;
        if (k < samples) {
          const Eigen::Vector2d uv =
              border.from_uv + (t0 + (k + 0.5) * (t1 - t0) / samples) * along;
          step = std::abs(paint(uv + across) - paint(uv - across)) >= options.min_albedo_step;
        }
        if (step && run_start < 0) {
          run_start = k;
        } else if (!step && run_start >= 0) {
          const double from_t = t0 + run_start * (t1 - t0) / samples;
          const double to_t = t0 + k * (t1 - t0) / samples;
          edges.push_back({wall.object_id, frame.point(border.from_uv + from_t * along),
                           frame.point(border.from_uv + to_t * along)});
          run_start = -1;
        }
      }
    }
  }
}

void addWallEdges(const CityWall& wall, const CityMesh& city,
                  const std::vector<Eigen::Vector2d>& near, const FacadeEdgeOptions& options,
                  std::vector<FacadeEdge>& edges) {
  if (!nearAny(wall, near, options.max_distance_m)) {
    return;
  }
  addWallFoot(wall, city, edges);
  for (const auto& triangle : wall.triangles) {
    addTriangleEdges(wall, triangle, options, edges);
  }
}

}  // namespace

std::vector<FacadeEdge> facadeDetailEdges(const CityMesh& city,
                                          const std::vector<Eigen::Vector2d>& near,
                                          const FacadeEdgeOptions& options) {
  if (!(options.sample_spacing_m > 0.0) || !(options.min_albedo_step > 0.0)) {
    throw std::invalid_argument("facadeDetailEdges: sample spacing and albedo step must be > 0");
  }
  std::vector<FacadeEdge> edges;
  for (const CityWall& wall : city.walls) {
    addWallEdges(wall, city, near, options, edges);
  }
  return edges;
}

void writeFacadeEdges(const std::string& path, const std::vector<FacadeEdge>& edges) {
  std::ofstream out(path);
  if (!out) {
    throw std::runtime_error(fmt::format("cannot write façade edges to {}", path));
  }
  out << "# object_id x0 y0 z0 x1 y1 z1 (m, site frame): the façade detail the images show\n";
  for (const FacadeEdge& edge : edges) {
    out << fmt::format("{} {:.4f} {:.4f} {:.4f} {:.4f} {:.4f} {:.4f}\n", edge.object_id,
                       edge.start.x(), edge.start.y(), edge.start.z(), edge.end.x(), edge.end.y(),
                       edge.end.z());
  }
}

std::vector<FacadeEdge> parseFacadeEdges(std::string_view text, const std::string& source) {
  std::vector<FacadeEdge> edges;
  forEachDataRow(text, [&](const std::string& line, int number) {
    std::istringstream fields(line);
    FacadeEdge edge;
    std::string rest;
    if (!(fields >> edge.object_id >> edge.start.x() >> edge.start.y() >> edge.start.z() >>
          edge.end.x() >> edge.end.y() >> edge.end.z()) ||
        (fields >> rest) || !edge.start.allFinite() || !edge.end.allFinite()) {
      throw std::runtime_error(
          fmt::format("{}:{}: expected 'object_id x0 y0 z0 x1 y1 z1' (finite numbers), got '{}'",
                      source, number, line));
    }
    edges.push_back(edge);
  });
  return edges;
}

std::vector<FacadeEdge> readFacadeEdges(const std::string& path) {
  return parseFacadeEdges(readTextFile(path, "façade edges"), path);
}

}  // namespace lineloc
