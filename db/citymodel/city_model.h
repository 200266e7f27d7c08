// The in-memory city model every reader produces and every consumer takes:
// buildings (CityJSON Building and BuildingPart objects) as planar faces with
// their semantic kind, in one CRS. It needs no database, so the loader, the
// line extraction and the simulator share it (paper §3.1: the 3D GIS model the
// lines come from).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace lineloc::citymodel {

// Codes as in the database table face_kind (CityJSON semantic surfaces).
enum class SurfaceKind : int16_t { kOther = 0, kWall = 1, kRoof = 2, kGround = 3 };

// A planar polygon: rings[0] is the exterior, the others are holes. Rings are
// open (the first vertex is not repeated at the end).
struct Face {
  SurfaceKind kind = SurfaceKind::kOther;
  std::vector<std::vector<Eigen::Vector3d>> rings;
};

struct Building {
  std::string id;         // the object's id in its source
  std::string parent_id;  // the Building a BuildingPart belongs to; empty otherwise
  std::string type;       // "Building" or "BuildingPart"
  std::string lod;        // the level of detail its faces come from; empty when it has none
  std::string attributes_json = "{}";  // the source's attributes, a JSON object
  std::vector<Face> faces;
};

// What a reader or validator left out or repaired, counted by reason ("not a
// building (Road)", "non-planar polygon", "non-planar face triangulated"), with
// the first few full messages.
struct SkippedObjects {
  std::map<std::string, int> count_by_reason;
  std::vector<std::string> messages;

  void add(const std::string& reason, const std::string& message);
  int total() const;
};

// One triangle of the terrain, counter-clockwise seen from above.
using TerrainTriangle = std::array<Eigen::Vector3d, 3>;

struct CityModel {
  std::optional<int> epsg;  // CRS named by the file, if any
  std::vector<Building> buildings;
  // The ground the buildings stand on (CityJSON TINRelief), empty when the
  // model has none.
  std::vector<TerrainTriangle> terrain;
  SkippedObjects skipped;
};

// Bad input: the message names the file and, where there is one, the object.
// `reason` is the category skipped objects are counted under ("non-planar
// polygon"); `detail` says where and by how much.
class ModelError : public std::runtime_error {
 public:
  ModelError(const std::string& source, const std::string& object_id, const std::string& reason,
             const std::string& detail = "");
  const std::string& reason() const { return reason_; }

 private:
  std::string reason_;
};

// What to do with an object that fails validation.
enum class InvalidObjectPolicy { kAbort, kSkip };

// The axis a file's coordinates hold up. lineloc's frames are z-up; many
// object models (OBJ from CAD and 3D tools) are y-up.
enum class UpAxis { kZ, kY };

// A file's point in lineloc's z-up frame: itself for kZ, (x, -z, y) for kY
// (a turn of +90 degrees about x, which takes the file's y to z).
Eigen::Vector3d zUpPoint(const Eigen::Vector3d& file_point, UpAxis up_axis);

// "z" or "y"; throws std::invalid_argument naming the string otherwise.
UpAxis parseUpAxis(const std::string& axis);

struct ReadOptions {
  // Level of detail to read ("2.2", "1"); empty: the highest present in the file.
  std::string lod;
  InvalidObjectPolicy invalid_objects = InvalidObjectPolicy::kAbort;
  // Deepest nesting of JSON arrays and objects a JSON reader accepts (a real
  // CityJSON or GeoJSON document nests about 10 levels); deeper input is
  // refused before it is parsed.
  int max_json_nesting = 256;
  // Up axis of CityJSON and OBJ coordinates (GeoJSON footprints are maps:
  // always z-up).
  UpAxis up_axis = UpAxis::kZ;
};

// Records `error` in `skipped` under kSkip, rethrows it under kAbort.
void handleInvalidObject(const ModelError& error, InvalidObjectPolicy policy,
                         SkippedObjects& skipped);

// The EPSG code named by a CRS string: "EPSG:7415", "urn:ogc:def:crs:EPSG::7415"
// or "https://www.opengis.net/def/crs/EPSG/0/7415". Throws std::invalid_argument
// naming the string when it is none of these.
int parseEpsgCode(const std::string& crs);

}  // namespace lineloc::citymodel
