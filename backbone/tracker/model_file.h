// A city model file (CityJSON, CityJSON Lines, OBJ, GeoJSON footprints, as
// lineloc-load reads them) turned into what the tracker needs: building lines
// and faces in a local frame, z-up, the file's coordinates minus `origin`. A
// file with a CRS (its own, or `file_epsg`) is kept in it; one without is an
// object in its own metric frame (a model of a machine, a mock-up), read as it
// is. A y-up file is turned z-up (citymodel::zUpPoint).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "backbone/tracker/model_tracker.h"
#include "db/citymodel/city_model.h"

namespace lineloc {

struct LocalModel {
  TrackedModel model;
  // In the file's coordinates.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  // The file names no CRS and was given none.
  bool local_frame = false;
  // Turns the local frame's axes into the file's (identity for a z-up file):
  // a pose in the model's own axes is changeWorldFrame(T_model_local, pose).
  Eigen::Isometry3d T_model_local = Eigen::Isometry3d::Identity();
  int buildings = 0;
};

// Reads `path`. `origin` (file coordinates) defaults to zero for a model in a
// local frame, and for one with a CRS to its lowest corner, rounded down to
// 100 m in x and y and to 1 m in z. `file_epsg` names the CRS of a file that
// names none. Throws std::runtime_error naming the file on bad input.
LocalModel readLocalModel(const std::string& path, std::optional<Eigen::Vector3d> origin,
                          std::optional<int> file_epsg,
                          citymodel::UpAxis up_axis = citymodel::UpAxis::kZ);

}  // namespace lineloc
