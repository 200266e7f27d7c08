// The render scene of a city model: every building face (CityJSON semantic
// wall or roof; ground faces lie under the ground and are left out)
// triangulated by ear clipping of its exterior ring (holes are not cut), and
// the model's terrain triangles as ground, moved by a site origin so
// coordinates stay small enough for float ray casting. Each building becomes
// one object, its façade style drawn from its index.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry/terrain_surface.h"
#include "db/citymodel/city_model.h"
#include "sim/render/scene_mesh.h"

namespace lineloc {

// A building's wall as rendered: its triangles in scene coordinates, each
// wound as the mesh holds it (the shader lays the façade out along each
// triangle's own normal), and what the shader paints on it (FacadeLayout of
// its object).
struct CityWall {
  uint32_t object_id = 0;
  float base_z = 0.0f;
  float top_z = 0.0f;
  std::vector<std::array<Eigen::Vector3d, 3>> triangles;
};

struct CityMesh {
  SceneMesh mesh;
  std::vector<CityWall> walls;
  // World (model CRS) coordinates of the scene's origin.
  Eigen::Vector3d site_origin = Eigen::Vector3d::Zero();
  // Height of the ground plane in scene coordinates: the street level of a
  // model without terrain (the median height of the buildings' bases), else
  // the terrain's lowest point, so that the plane lies under the terrain and
  // shows only beyond its edge.
  double ground_z_m = 0.0;
  // The terrain in scene coordinates; empty when the model has none.
  TerrainSurface terrain{{}};
  int building_count = 0;
  // Faces left out because their ring could not be triangulated.
  int skipped_faces = 0;
};

// The ground's height under a scene point: the terrain's where it has one,
// else the ground plane's.
double groundHeightAt(const CityMesh& city, const Eigen::Vector2d& xy);

// Object ids 1..N are the buildings; the terrain is kTerrainObjectId; clutter
// takes ids from kFirstClutterObjectId on.
inline constexpr uint32_t kTerrainObjectId = 999'999;
inline constexpr uint32_t kFirstClutterObjectId = 1'000'000;
// Street furniture's (street_furniture.h): after every clutter object's.
inline constexpr uint32_t kFirstFurnitureObjectId = 2'000'000;

// Builds the scene with the given origin. Throws std::invalid_argument when the
// model has no buildings.
CityMesh buildCityMesh(const citymodel::CityModel& model, const Eigen::Vector3d& site_origin);

// The centre of the buildings' xy bounding box rounded to metres, height 0:
// the default site origin.
Eigen::Vector3d defaultSiteOrigin(const citymodel::CityModel& model);

// `site_origin` (model coordinates x y z) when given, else defaultSiteOrigin.
// Throws std::invalid_argument when it holds other than three numbers.
Eigen::Vector3d siteOriginOf(const citymodel::CityModel& model,
                             const std::vector<double>& site_origin);

// Reads a CityJSON or CityJSON Lines (.jsonl) file into a model (buildings at
// the highest level of detail). Throws naming the file when it is unreadable
// or malformed.
citymodel::CityModel readCityModelFile(const std::string& path);

}  // namespace lineloc
