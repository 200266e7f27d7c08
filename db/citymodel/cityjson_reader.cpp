#include "db/citymodel/cityjson_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "common/geometry/polygon_triangulation.h"
#include "db/citymodel/json_document.h"
#include "db/citymodel/polygon_geometry.h"

namespace lineloc::citymodel {
namespace {

using Json = nlohmann::json;

struct Transform {
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  Eigen::Vector3d translate = Eigen::Vector3d::Zero();
};

// A Building or BuildingPart with its faces at every level of detail it has.
struct ParsedObject {
  Building building;
  std::map<std::string, std::vector<Face>> faces_by_lod;
  bool has_children = false;
};

// A structural defect inside one object, turned into a ModelError by the caller.
struct ObjectDefect {
  std::string reason;
  std::string detail;
};

Eigen::Vector3d readTriple(const Json& value, const std::string& source, const std::string& key) {
  if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() ||
      !value[2].is_number()) {
    throw ModelError(source, "", "malformed transform", key + " must be 3 numbers");
  }
  return {value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
}

Transform readTransform(const Json& document, const std::string& source) {
  Transform transform;
  const auto found = document.find("transform");
  if (found == document.end()) {
    return transform;
  }
  if (!found->is_object() || !found->contains("scale") || !found->contains("translate")) {
    throw ModelError(source, "", "malformed transform", "needs 'scale' and 'translate'");
  }
  transform.scale = readTriple((*found)["scale"], source, "scale");
  transform.translate = readTriple((*found)["translate"], source, "translate");
  if (!transform.scale.allFinite() || !transform.translate.allFinite()) {
    throw ModelError(source, "", "malformed transform", "non-finite value");
  }
  return transform;
}

std::optional<int> readEpsg(const Json& document, const std::string& source) {
  const auto metadata = document.find("metadata");
  if (metadata == document.end() || !metadata->is_object()) {
    return std::nullopt;
  }
  const auto reference_system = metadata->find("referenceSystem");
  if (reference_system == metadata->end() || !reference_system->is_string()) {
    return std::nullopt;
  }
  try {
    return parseEpsgCode(reference_system->get<std::string>());
  } catch (const std::invalid_argument& error) {
    throw ModelError(source, "", "unknown CRS", error.what());
  }
}

std::vector<Eigen::Vector3d> readVertices(const Json& vertices, const Transform& transform,
                                          UpAxis up_axis, const std::string& source) {
  if (!vertices.is_array()) {
    throw ModelError(source, "", "malformed vertices", "'vertices' must be an array");
  }
  std::vector<Eigen::Vector3d> points;
  points.reserve(vertices.size());
  for (const Json& vertex : vertices) {
    if (!vertex.is_array() || vertex.size() != 3 || !vertex[0].is_number() ||
        !vertex[1].is_number() || !vertex[2].is_number()) {
      throw ModelError(source, "", "malformed vertices",
                       fmt::format("vertex {} is not 3 numbers", points.size()));
    }
    const Eigen::Vector3d raw(vertex[0].get<double>(), vertex[1].get<double>(),
                              vertex[2].get<double>());
    const Eigen::Vector3d point = transform.scale.cwiseProduct(raw) + transform.translate;
    if (!point.allFinite()) {
      throw ModelError(source, "", "non-finite vertex coordinate",
                       fmt::format("vertex {}", points.size()));
    }
    points.push_back(zUpPoint(point, up_axis));
  }
  return points;
}

std::string lodName(const Json& lod) {
  if (lod.is_string()) {
    return lod.get<std::string>();
  }
  if (lod.is_number_integer() || lod.is_number_unsigned()) {
    return std::to_string(lod.get<int64_t>());
  }
  if (lod.is_number_float()) {
    return fmt::format("{}", lod.get<double>());
  }
  throw ObjectDefect{"malformed geometry", "'lod' must be a string or a number"};
}

double lodValue(const std::string& lod) {
  try {
    return std::stod(lod);
  } catch (const std::exception&) {
    return -1.0;
  }
}

SurfaceKind semanticKind(const std::string& type) {
  if (type == "WallSurface")
    return SurfaceKind::kWall;
  if (type == "RoofSurface")
    return SurfaceKind::kRoof;
  if (type == "GroundSurface")
    return SurfaceKind::kGround;
  return SurfaceKind::kOther;
}

// Reads one object's geometries; the semantic surface array and the vertex pool
// are shared by its surfaces.
class GeometryReader {
 public:
  explicit GeometryReader(const std::vector<Eigen::Vector3d>& vertices) : vertices_(vertices) {}

  std::vector<Face> read(const Json& geometry) {
    const std::string type = geometry.value("type", "");
    const int depth = nestingDepth(type);
    std::vector<SurfaceKind> kinds;
    const Json* values = nullptr;
    if (const auto semantics = geometry.find("semantics"); semantics != geometry.end()) {
      kinds = semanticKinds(*semantics);
      if (const auto found = semantics->find("values"); found != semantics->end()) {
        values = &*found;
      }
    }
    const auto boundaries = geometry.find("boundaries");
    if (boundaries == geometry.end()) {
      throw ObjectDefect{"malformed geometry", "no 'boundaries'"};
    }
    std::vector<Face> faces;
    collect(*boundaries, values, depth, kinds, faces);
    return faces;
  }

 private:
  static int nestingDepth(const std::string& type) {
    if (type == "MultiSurface" || type == "CompositeSurface" || type == "TIN")
      return 0;
    if (type == "Solid")
      return 1;
    if (type == "MultiSolid" || type == "CompositeSolid")
      return 2;
    throw ObjectDefect{"unsupported geometry type", type};
  }

  static std::vector<SurfaceKind> semanticKinds(const Json& semantics) {
    std::vector<SurfaceKind> kinds;
    const auto surfaces = semantics.find("surfaces");
    if (surfaces == semantics.end() || !surfaces->is_array()) {
      throw ObjectDefect{"malformed semantics", "no 'surfaces' array"};
    }
    for (const Json& surface : *surfaces) {
      kinds.push_back(surface.is_object() ? semanticKind(surface.value("type", ""))
                                          : SurfaceKind::kOther);
    }
    return kinds;
  }

  void collect(const Json& boundaries, const Json* values, int depth,
               const std::vector<SurfaceKind>& kinds, std::vector<Face>& faces) const {
    if (!boundaries.is_array()) {
      throw ObjectDefect{"malformed geometry", "boundaries nest wrongly for the geometry type"};
    }
    const bool values_are_array = values != nullptr && values->is_array();
    for (size_t i = 0; i < boundaries.size(); ++i) {
      const Json* child_values = values_are_array && i < values->size() ? &(*values)[i] : nullptr;
      if (depth > 0) {
        collect(boundaries[i], child_values, depth - 1, kinds, faces);
      } else {
        faces.push_back(readSurface(boundaries[i], child_values, kinds));
      }
    }
  }

  Face readSurface(const Json& surface, const Json* value,
                   const std::vector<SurfaceKind>& kinds) const {
    if (!surface.is_array() || surface.empty()) {
      throw ObjectDefect{"malformed geometry", "a surface must be a non-empty array of rings"};
    }
    Face face;
    for (const Json& ring : surface) {
      face.rings.push_back(readRing(ring));
    }
    if (value != nullptr && value->is_number_unsigned() && value->get<size_t>() < kinds.size()) {
      face.kind = kinds[value->get<size_t>()];
    } else if (value != nullptr && !value->is_null()) {
      throw ObjectDefect{"malformed semantics", "semantic value is not an index into 'surfaces'"};
    } else {
      face.kind = surfaceKindFromNormal(faceNormal(face));
    }
    return face;
  }

  std::vector<Eigen::Vector3d> readRing(const Json& ring) const {
    if (!ring.is_array()) {
      throw ObjectDefect{"malformed geometry", "a ring must be an array of vertex indices"};
    }
    std::vector<Eigen::Vector3d> points;
    points.reserve(ring.size());
    int64_t previous = -1;
    for (const Json& index : ring) {
      if (!index.is_number_unsigned() || index.get<uint64_t>() >= vertices_.size()) {
        throw ObjectDefect{
            "vertex index out of range",
            fmt::format("index {} with {} vertices", index.dump(), vertices_.size())};
      }
      const int64_t current = index.get<int64_t>();
      if (current != previous) {
        points.push_back(vertices_[current]);
      }
      previous = current;
    }
    if (points.size() > 1 && points.front() == points.back()) {
      points.pop_back();
    }
    return points;
  }

  const std::vector<Eigen::Vector3d>& vertices_;
};

bool isBuilding(const std::string& type) {
  return type == "Building" || type == "BuildingPart";
}

// The triangles of a TINRelief's geometry of the highest level of detail,
// each turned counter-clockwise seen from above; faces with more than three
// vertices are triangulated, vertical ones carry no height and are left out.
std::vector<TerrainTriangle> readTerrain(const Json& object,
                                         const std::vector<Eigen::Vector3d>& vertices) {
  const auto geometries = object.find("geometry");
  if (geometries == object.end() || !geometries->is_array()) {
    throw ObjectDefect{"malformed geometry", "'geometry' must be an array"};
  }
  const Json* highest = nullptr;
  double highest_lod = -1.0;
  for (const Json& geometry : *geometries) {
    if (!geometry.is_object() || !geometry.contains("lod")) {
      throw ObjectDefect{"malformed geometry", "a geometry must be an object with a 'lod'"};
    }
    const double lod = lodValue(lodName(geometry["lod"]));
    if (highest == nullptr || lod > highest_lod) {
      highest = &geometry;
      highest_lod = lod;
    }
  }
  std::vector<TerrainTriangle> triangles;
  if (highest == nullptr) {
    return triangles;
  }
  for (const Face& face : GeometryReader(vertices).read(*highest)) {
    const std::vector<Eigen::Vector3d>& ring = face.rings.front();
    for (const std::array<int, 3>& corners : triangulatePolygon(ring)) {
      TerrainTriangle triangle{ring[corners[0]], ring[corners[1]], ring[corners[2]]};
      const Eigen::Vector3d ab = triangle[1] - triangle[0];
      const Eigen::Vector3d ac = triangle[2] - triangle[0];
      const double up = ab.x() * ac.y() - ab.y() * ac.x();
      if (up < 0.0) {
        std::swap(triangle[1], triangle[2]);
      }
      if (up != 0.0) {
        triangles.push_back(triangle);
      }
    }
  }
  return triangles;
}

ParsedObject parseObject(const std::string& id, const Json& object,
                         const std::vector<Eigen::Vector3d>& vertices) {
  ParsedObject parsed;
  parsed.building.id = id;
  parsed.building.type = object.value("type", "");
  if (const auto parents = object.find("parents"); parents != object.end() && parents->is_array() &&
                                                   !parents->empty() && (*parents)[0].is_string()) {
    parsed.building.parent_id = (*parents)[0].get<std::string>();
  }
  if (const auto children = object.find("children"); children != object.end()) {
    parsed.has_children = children->is_array() && !children->empty();
  }
  if (const auto attributes = object.find("attributes");
      attributes != object.end() && attributes->is_object()) {
    parsed.building.attributes_json = attributes->dump();
  }
  const auto geometries = object.find("geometry");
  if (geometries == object.end()) {
    return parsed;
  }
  if (!geometries->is_array()) {
    throw ObjectDefect{"malformed geometry", "'geometry' must be an array"};
  }
  GeometryReader reader(vertices);
  for (const Json& geometry : *geometries) {
    if (!geometry.is_object()) {
      throw ObjectDefect{"malformed geometry", "a geometry must be an object"};
    }
    if (geometry.value("type", "") == "GeometryInstance") {
      continue;
    }
    const auto lod = geometry.find("lod");
    if (lod == geometry.end()) {
      throw ObjectDefect{"malformed geometry", "no 'lod'"};
    }
    std::vector<Face> faces = reader.read(geometry);
    auto& slot = parsed.faces_by_lod[lodName(*lod)];
    slot.insert(slot.end(), std::make_move_iterator(faces.begin()),
                std::make_move_iterator(faces.end()));
  }
  return parsed;
}

// Parses the CityObjects of one document or feature into `objects` and the
// model's terrain; other object types and invalid objects go to its skipped
// objects (or throw, by policy).
void parseObjects(const Json& city_objects, const std::vector<Eigen::Vector3d>& vertices,
                  const std::string& source, const ReadOptions& options,
                  std::vector<ParsedObject>& objects, CityModel& model) {
  SkippedObjects& skipped = model.skipped;
  if (!city_objects.is_object()) {
    throw ModelError(source, "", "malformed CityJSON", "'CityObjects' must be an object");
  }
  for (const auto& [id, object] : city_objects.items()) {
    const std::string type = object.is_object() ? object.value("type", "") : "";
    if (type == "TINRelief") {
      try {
        const std::vector<TerrainTriangle> triangles = readTerrain(object, vertices);
        model.terrain.insert(model.terrain.end(), triangles.begin(), triangles.end());
      } catch (const ObjectDefect& defect) {
        handleInvalidObject(ModelError(source, id, defect.reason, defect.detail),
                            options.invalid_objects, skipped);
      }
      continue;
    }
    if (!isBuilding(type)) {
      skipped.add(fmt::format("not a building ({})", type),
                  fmt::format("{}: object '{}': not a building ({})", source, id, type));
      continue;
    }
    try {
      objects.push_back(parseObject(id, object, vertices));
    } catch (const ObjectDefect& defect) {
      handleInvalidObject(ModelError(source, id, defect.reason, defect.detail),
                          options.invalid_objects, skipped);
    } catch (const Json::exception& error) {
      handleInvalidObject(ModelError(source, id, "malformed object", error.what()),
                          options.invalid_objects, skipped);
    }
  }
}

std::string chooseLod(const std::vector<ParsedObject>& objects, const std::string& source,
                      const std::string& requested) {
  std::set<std::string> present;
  for (const ParsedObject& object : objects) {
    for (const auto& [lod, faces] : object.faces_by_lod) {
      present.insert(lod);
    }
  }
  std::vector<std::string> candidates;
  for (const std::string& lod : present) {
    const bool matches =
        requested.empty() || lod == requested ||
        (requested.find('.') == std::string::npos && lod.rfind(requested + ".", 0) == 0);
    if (matches) {
      candidates.push_back(lod);
    }
  }
  if (candidates.empty()) {
    if (present.empty()) {
      return "";
    }
    throw ModelError(
        source, "", "LoD not in file",
        fmt::format("asked for LoD {}, the file has {}", requested, fmt::join(present, ", ")));
  }
  return *std::max_element(
      candidates.begin(), candidates.end(),
      [](const std::string& a, const std::string& b) { return lodValue(a) < lodValue(b); });
}

CityModel assemble(std::vector<ParsedObject> objects, const std::string& source,
                   const ReadOptions& options, CityModel model) {
  const std::string lod = chooseLod(objects, source, options.lod);
  for (ParsedObject& object : objects) {
    auto faces = object.faces_by_lod.find(lod);
    if (faces != object.faces_by_lod.end()) {
      object.building.lod = lod;
      object.building.faces = std::move(faces->second);
    } else if (!object.has_children) {
      const std::string reason = fmt::format("no geometry at LoD {}", lod);
      model.skipped.add(reason,
                        fmt::format("{}: object '{}': {}", source, object.building.id, reason));
      continue;
    }
    model.buildings.push_back(std::move(object.building));
  }
  return model;
}

// Turns nlohmann's type errors in the document's frame (outside any object)
// into ModelError.
template <typename Read>
CityModel translatingJsonErrors(const std::string& source, Read&& read) {
  try {
    return read();
  } catch (const Json::exception& error) {
    throw ModelError(source, "", "malformed CityJSON", error.what());
  }
}

CityModel readDocument(std::string_view text, const std::string& source,
                       const ReadOptions& options) {
  const Json document = parseJsonDocument(text, source, "", options.max_json_nesting);
  if (!document.is_object() || document.value("type", "") != "CityJSON") {
    throw ModelError(source, "", "malformed CityJSON", "top level must be a CityJSON object");
  }
  CityModel model;
  model.epsg = readEpsg(document, source);
  const Transform transform = readTransform(document, source);
  const auto vertices = document.find("vertices");
  const auto city_objects = document.find("CityObjects");
  if (vertices == document.end() || city_objects == document.end()) {
    throw ModelError(source, "", "malformed CityJSON", "needs 'vertices' and 'CityObjects'");
  }
  const std::vector<Eigen::Vector3d> points =
      readVertices(*vertices, transform, options.up_axis, source);
  std::vector<ParsedObject> objects;
  parseObjects(*city_objects, points, source, options, objects, model);
  return assemble(std::move(objects), source, options, std::move(model));
}

CityModel readLines(std::string_view text, const std::string& source, const ReadOptions& options) {
  CityModel model;
  std::vector<ParsedObject> objects;
  std::optional<Transform> transform;
  int line_number = 0;
  size_t begin = 0;
  while (begin < text.size()) {
    const size_t end = std::min(text.find('\n', begin), text.size());
    const std::string_view line = text.substr(begin, end - begin);
    begin = end + 1;
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) {
      continue;
    }
    const std::string where = fmt::format("line {}", line_number);
    if (!transform) {
      const Json header = parseJsonDocument(line, source, where + ": ", options.max_json_nesting);
      if (!header.is_object() || header.value("type", "") != "CityJSON") {
        throw ModelError(source, "", "malformed CityJSON Lines",
                         "the first line must be a CityJSON object");
      }
      model.epsg = readEpsg(header, source);
      transform = readTransform(header, source);
      continue;
    }
    const std::string feature_source = fmt::format("{}:{}", source, line_number);
    try {
      const Json feature = parseJsonDocument(line, source, where + ": ", options.max_json_nesting);
      if (!feature.is_object() || !feature.contains("CityObjects") ||
          !feature.contains("vertices")) {
        throw ModelError(feature_source, "", "malformed CityJSONFeature",
                         "needs 'CityObjects' and 'vertices'");
      }
      const std::vector<Eigen::Vector3d> points =
          readVertices(feature["vertices"], *transform, options.up_axis, feature_source);
      parseObjects(feature["CityObjects"], points, feature_source, options, objects, model);
    } catch (const ModelError& error) {
      handleInvalidObject(error, options.invalid_objects, model.skipped);
    }
  }
  if (!transform) {
    throw ModelError(source, "", "malformed CityJSON Lines", "no CityJSON header line");
  }
  return assemble(std::move(objects), source, options, std::move(model));
}

}  // namespace

CityModel readCityJson(std::string_view text, const std::string& source,
                       const ReadOptions& options) {
  return translatingJsonErrors(source, [&] { return readDocument(text, source, options); });
}

CityModel readCityJsonLines(std::string_view text, const std::string& source,
                            const ReadOptions& options) {
  return translatingJsonErrors(source, [&] { return readLines(text, source, options); });
}

}  // namespace lineloc::citymodel
