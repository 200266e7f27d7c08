// The backbone's tile query: the model lines of every building whose box meets
// a square of the ground plane (ModelLineQuery's line packs), and every face
// and terrain triangle whose bounding box meets it (2D GiST indexes, binary
// EWKB), decoded into world-frame (site CRS minus origin) Eigen values; when
// asked, the confirmed learnt lines that meet it (db/enrichment_store.h).
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "db/connection.h"
#include "db/model_line_query.h"
#include "db/site.h"

namespace lineloc::db {

struct ModelFaceRecord {
  int64_t id = 0;
  int64_t building_id = 0;
  int16_t kind = 0;
  // Exterior ring in world coordinates, without the closing vertex.
  std::vector<Eigen::Vector3d> ring_world;
};

// One triangle of the terrain, counter-clockwise seen from above.
struct TerrainTriangleRecord {
  int64_t id = 0;
  std::array<Eigen::Vector3d, 3> corners_world;
};

// A confirmed learnt line (db/enrichment_store.h) in world coordinates, with
// the larger of its ends' largest standard deviations in any direction: never
// less than across the line, which is what matching weighs.
struct LearntLineRecord {
  int64_t id = 0;
  Eigen::Vector3d start_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_world = Eigen::Vector3d::Zero();
  double sigma_m = 0.0;
};

struct TileContents {
  std::vector<ModelLine> lines;
  std::vector<ModelFaceRecord> faces;
  // Empty where the model has no terrain.
  std::vector<TerrainTriangleRecord> terrain;
  // Empty unless the query was asked for them.
  std::vector<LearntLineRecord> learnt_lines;
};

class MapTileQuery {
 public:
  // Prepares the statements on `connection` (once per session), which must
  // outlive this object. With `learnt_lines`, tiles hold the site's confirmed
  // learnt lines too.
  MapTileQuery(Connection& connection, const Site& site, bool learnt_lines = false);

  // Lines, faces, terrain triangles (and learnt lines) whose bounding box
  // meets `bounds_world` (x, y; any height).
  TileContents within(const Eigen::AlignedBox2d& bounds_world);

 private:
  Connection& connection_;
  Site site_;
  ModelLineQuery lines_;
  bool learnt_lines_;
};

}  // namespace lineloc::db
