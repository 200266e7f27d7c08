// The backbone's map query: the model's 3D building lines within a radius of a
// position, through a prepared statement with binary results, decoded straight
// into world-frame (site-local) Eigen segments.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "db/connection.h"
#include "db/site.h"

namespace lineloc::db {

enum class LineKind : int16_t { kOther = 0, kVertical = 1, kEave = 2, kRidge = 3, kGround = 4 };

struct ModelLine {
  int64_t id = 0;
  int64_t building_id = 0;
  LineKind kind = LineKind::kOther;
  Eigen::Vector3d start_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_world = Eigen::Vector3d::Zero();
};

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
