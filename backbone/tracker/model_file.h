// A city model file (CityJSON, CityJSON Lines, OBJ, GeoJSON footprints, as
// lineloc-load reads them) turned into what the tracker needs: building lines
// and faces in a local frame, the file's CRS minus `origin`.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "backbone/tracker/model_tracker.h"

namespace lineloc {

struct LocalModel {
  TrackedModel model;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  int buildings = 0;
};

// Reads `path`; `origin` defaults to the model's lowest corner, rounded down to
// 100 m in x and y and to 1 m in z. `file_epsg` is needed only for a file that
// names no CRS. Throws std::runtime_error naming the file on bad input.
LocalModel readLocalModel(const std::string& path, std::optional<Eigen::Vector3d> origin,
                          std::optional<int> file_epsg);

}  // namespace lineloc
