// Coordinate transformation between two EPSG CRSs with PROJ, in the
// east-north-up axis order lineloc uses (proj_normalize_for_visualization), so
// a model is moved into its site's CRS before lines are derived from it.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "db/citymodel/city_model.h"

namespace lineloc::citymodel {

class CrsTransform {
 public:
  // Throws std::invalid_argument naming the codes when PROJ knows no
  // transformation between them.
  CrsTransform(int source_epsg, int target_epsg);
  ~CrsTransform();
  CrsTransform(const CrsTransform&) = delete;
  CrsTransform& operator=(const CrsTransform&) = delete;

  bool isIdentity() const { return source_epsg_ == target_epsg_; }

  // Throws std::domain_error when the point is outside the transformation's domain.
  Eigen::Vector3d apply(const Eigen::Vector3d& point) const;

  // Transforms every vertex of every building and of the terrain; a building
  // whose vertex cannot be transformed is an invalid object (ModelError naming
  // `source` and it), and so is the terrain as a whole.
  void apply(CityModel& model, const std::string& source, InvalidObjectPolicy policy) const;

 private:
  struct Proj;
  int source_epsg_;
  int target_epsg_;
  std::unique_ptr<Proj> proj_;
};

}  // namespace lineloc::citymodel
