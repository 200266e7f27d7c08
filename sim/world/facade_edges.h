// The 3D edges the simulator's images show on a city's walls that its model
// lacks: the façade detail it paints (FacadeLayout: window and door frames,
// mullions, signs) and the wall's foot where it meets the rendered ground
// (the terrain, or the ground plane), which the model's ground line only
// approximates. The ground truth that lines learnt from its images are scored
// against.
//
// Each wall triangle's element borders are clipped to the triangle in wall
// coordinates laid out along its own normal, as the shader lays them: u along
// the wall, v up from the building's base; a point (u, v) lies at
// u t + s n_h + (base + v) z, with t and n_h the triangle's horizontal tangent
// and normal and s = (n . p0 - n_z (base + v)) / |n_xy| on its plane
// n . x = n . p0. A piece is kept where the painted albedo steps across it by
// at least min_albedo_step, sampled every sample_spacing_m. A wall's foot is
// sampled every 0.25 m and merged into straight runs (every sample within 1 cm
// of the run's chord). Walls farther than max_distance_m from every point of
// `near` are left out (the cameras of a drive never resolve them).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sim/world/city_mesh.h"

namespace lineloc {

struct FacadeEdge {
  uint32_t object_id = 0;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();  // scene (site) frame, m
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
};

struct FacadeEdgeOptions {
  double min_albedo_step = 0.05;
  double sample_spacing_m = 0.01;
  double max_distance_m = 100.0;
};

std::vector<FacadeEdge> facadeDetailEdges(const CityMesh& city,
                                          const std::vector<Eigen::Vector2d>& near,
                                          const FacadeEdgeOptions& options = {});

// One edge per line: object_id x0 y0 z0 x1 y1 z1, after a '#' header.
void writeFacadeEdges(const std::string& path, const std::vector<FacadeEdge>& edges);
// Parses that text; `source` names it in errors. Throws std::runtime_error
// naming the source and line of a malformed row.
std::vector<FacadeEdge> parseFacadeEdges(std::string_view text, const std::string& source);
std::vector<FacadeEdge> readFacadeEdges(const std::string& path);

}  // namespace lineloc
