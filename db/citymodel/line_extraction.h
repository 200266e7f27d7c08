// The 3D lines a camera can see on a building, derived from its faces (paper
// §3.1: the database holds the building edges the matcher projects).
//
// Every polygon edge becomes a segment. Edges are welded across faces (shared
// vertices within `vertex_snap_m`, and T-junctions split, so an edge shared by
// two faces is one line with both faces). An edge whose two faces are nearly
// coplanar, dihedral angle acos(|n_a . n_b|) below `coplanar_angle_rad`
// (triangulation diagonals, a wall split in two), is not a visible crease and
// is dropped; collinear pieces of one crease between the same two planes are
// merged back into one line. Each line gets its kind and both face normals, so
// the matcher can predict which side is brighter and which edges can show
// against the sky.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

#include "db/citymodel/city_model.h"

namespace lineloc::citymodel {

// Codes as in the database table line_kind; kLearnt, a line learnt from the
// robots' images (db/enrichment_store.h), is never in table line.
enum class LineKind : int16_t {
  kOther = 0,
  kVertical = 1,
  kEave = 2,
  kRidge = 3,
  kGround = 4,
  kLearnt = 5
};

struct LineExtractionOptions {
  double coplanar_angle_rad = 10.0 * M_PI / 180.0;
  double vertex_snap_m = 1e-3;
  // A vertex this close to the inside of another face's edge splits that edge.
  double t_junction_tolerance_m = 5e-3;
  // Lines within this angle of the vertical are vertical; within it of the
  // horizontal they can be eaves, ridges or ground lines.
  double direction_tolerance_rad = 10.0 * M_PI / 180.0;
};

struct ExtractedLine {
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  LineKind kind = LineKind::kOther;
  int face_a = -1;                                     // index into the building's faces
  int face_b = -1;                                     // -1 when the edge borders one face only
  Eigen::Vector3d normal_a = Eigen::Vector3d::Zero();  // outward unit normals
  Eigen::Vector3d normal_b = Eigen::Vector3d::Zero();  // zero when face_b is -1
};

// Kinds: vertical (direction within tolerance of z); ground (horizontal, on a
// ground face or at the building's lowest height); ridge (horizontal, convex,
// between two roof faces); eave (horizontal, convex, between a roof and a wall,
// or the free border of a roof); other (hips, valleys, steps).
std::vector<ExtractedLine> extractLines(const std::vector<Face>& faces,
                                        const LineExtractionOptions& options = {});

}  // namespace lineloc::citymodel
