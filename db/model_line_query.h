// The backbone's map queries (paper §3.1: the lines near the robot, fast): the
// model's 3D building lines within a radius of a position, or inside a
// camera's view frustum. A prepared statement selects the buildings whose
// packed 2D bounds meet the query's box (table building_line_pack, a GiST
// index with one entry per building) and returns their line packs as binary
// bytea; the exact test (3D segment-point distance, or frustum clipping) runs
// here while decoding into world-frame (site-local) Eigen segments.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "common/camera/camera_calibration.h"
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

class ModelLineQuery {
 public:
  // Prepares the statement on `connection` (once per session), which must
  // outlive this object.
  ModelLineQuery(Connection& connection, const Site& site);

  // Lines with any point within `radius_m` (3D distance) of `center_world`.
  std::vector<ModelLine> linesWithin(const Eigen::Vector3d& center_world, double radius_m);

  // Lines with any point inside the view frustum of `camera` at
  // `T_world_camera`, between depths `near_m` and `far_m` (see ViewFrustum;
  // throws std::invalid_argument as it does).
  std::vector<ModelLine> linesInFrustum(const Eigen::Isometry3d& T_world_camera,
                                        const PinholeCamera& camera, double near_m, double far_m);

  // Every line of the buildings whose packed bounds meet `bounds_world` (x, y;
  // any height), unfiltered: the lines of a map tile.
  std::vector<ModelLine> linesOfBuildingsMeeting(const Eigen::AlignedBox2d& bounds_world);

 private:
  Connection& connection_;
  Site site_;
};

}  // namespace lineloc::db
