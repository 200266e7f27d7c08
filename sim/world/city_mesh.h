// The render scene of a city model: every building face (CityJSON semantic
// wall or roof; ground faces lie under the ground plane and are left out)
// triangulated by ear clipping of its exterior ring (holes are not cut), moved
// by a site origin so coordinates stay small enough for float ray casting.
// Each building becomes one object, its façade style drawn from its index.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "db/citymodel/city_model.h"
#include "sim/render/scene_mesh.h"

namespace lineloc {

struct CityMesh {
  SceneMesh mesh;
  // World (model CRS) coordinates of the scene's origin.
  Eigen::Vector3d site_origin = Eigen::Vector3d::Zero();
  // Median height of the buildings' bases in scene coordinates: the street level.
  double ground_z_m = 0.0;
  int building_count = 0;
  // Faces left out because their ring could not be triangulated.
  int skipped_faces = 0;
};

// Object ids 1..N are the buildings; clutter takes ids from here on.
inline constexpr uint32_t kFirstClutterObjectId = 1'000'000;

// Builds the scene with the given origin. Throws std::invalid_argument when the
// model has no buildings.
CityMesh buildCityMesh(const citymodel::CityModel& model, const Eigen::Vector3d& site_origin);

// The centre of the buildings' xy bounding box rounded to metres, height 0:
// the default site origin.
Eigen::Vector3d defaultSiteOrigin(const citymodel::CityModel& model);

// Reads a CityJSON or CityJSON Lines (.jsonl) file into a model (buildings at
// the highest level of detail). Throws naming the file when it is unreadable
// or malformed.
citymodel::CityModel readCityModelFile(const std::string& path);

}  // namespace lineloc
