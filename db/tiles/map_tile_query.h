// The backbone's tile query: the model lines of every building whose box meets
// a square of the ground plane (ModelLineQuery's line packs), and every face
// and terrain triangle whose bounding box meets it (2D GiST indexes, binary
// EWKB), decoded into world-frame (site CRS minus origin) Eigen values.
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

struct TileContents {
  std::vector<ModelLine> lines;
  std::vector<ModelFaceRecord> faces;
  // Empty where the model has no terrain.
  std::vector<TerrainTriangleRecord> terrain;
};

class MapTileQuery {
 public:
  // Prepares the statements on `connection` (once per session), which must
  // outlive this object.
  MapTileQuery(Connection& connection, const Site& site);

  // Lines, faces and terrain triangles whose bounding box meets `bounds_world` (x, y; any height).
  TileContents within(const Eigen::AlignedBox2d& bounds_world);

 private:
  Connection& connection_;
  Site site_;
  ModelLineQuery lines_;
};

}  // namespace lineloc::db
