// The backbone's map query (paper §3.1: the lines near the robot, fast): the
// model's 3D building lines within a radius of a position. A prepared
// statement selects candidates with the n-D GiST index (the &&& box test
// alone) and returns the geometry as binary EWKB; the exact 3D segment-point
// distance test runs here while decoding into world-frame (site-local) Eigen
// segments, which is cheaper than ST_3DDWithin on the server.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "db/citymodel/line_extraction.h"
#include "db/connection.h"
#include "db/site.h"

namespace lineloc::db {

using LineKind = citymodel::LineKind;

struct ModelLine {
  int64_t id = 0;
  int64_t building_id = 0;
  LineKind kind = LineKind::kOther;
  Eigen::Vector3d start_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_world = Eigen::Vector3d::Zero();
  // Ordinals (within the building) and outward unit normals of the faces the
  // line lies between; -1 and zero when absent (a free border, or a line not
  // derived from faces).
  int face_a = -1;
  int face_b = -1;
  Eigen::Vector3d normal_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_b = Eigen::Vector3d::Zero();
};

// The columns of a model line query, in the order decodeModelLine reads them.
inline constexpr const char* kModelLineColumns =
    "id, building_id, kind, geom, face_a, face_b, normal_a_x, normal_a_y, normal_a_z, "
    "normal_b_x, normal_b_y, normal_b_z";

// Decodes row `row` of a binary-format result selecting kModelLineColumns into
// world coordinates (site CRS minus `origin`). Throws DatabaseError when the
// geometry is not a 2-point LINESTRING Z.
ModelLine decodeModelLine(const Result& result, int row, const Eigen::Vector3d& origin);

class ModelLineQuery {
 public:
  // Prepares the statement on `connection`, which must outlive this object.
  ModelLineQuery(Connection& connection, const Site& site);

  // Lines with any point within `radius_m` (3D distance) of `center_world`.
  std::vector<ModelLine> linesWithin(const Eigen::Vector3d& center_world, double radius_m);

 private:
  Connection& connection_;
  Site site_;
};

}  // namespace lineloc::db
