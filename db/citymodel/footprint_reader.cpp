#include "db/citymodel/footprint_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "db/citymodel/json_document.h"

namespace lineloc::citymodel {
namespace {

using Json = nlohmann::json;

struct FeatureDefect {
  std::string reason;
  std::string detail;
};

// Twice the signed area (shoelace), positive for counter-clockwise rings.
double signedArea2(const std::vector<Eigen::Vector2d>& ring) {
  double sum = 0.0;
  for (size_t i = 0; i < ring.size(); ++i) {
    const Eigen::Vector2d& a = ring[i];
    const Eigen::Vector2d& b = ring[(i + 1) % ring.size()];
    sum += a.x() * b.y() - b.x() * a.y();
  }
  return sum;
}

std::vector<Eigen::Vector3d> atHeight(const std::vector<Eigen::Vector2d>& ring, double z) {
  std::vector<Eigen::Vector3d> lifted;
  lifted.reserve(ring.size());
  for (const Eigen::Vector2d& point : ring) {
    lifted.emplace_back(point.x(), point.y(), z);
  }
  return lifted;
}

struct Footprint {
  std::vector<std::vector<Eigen::Vector2d>> rings;
  std::optional<double> z;
};

Footprint readPolygon(const Json& polygon) {
  if (!polygon.is_array() || polygon.empty()) {
    throw FeatureDefect{"malformed geometry", "a polygon must be a non-empty array of rings"};
  }
  Footprint footprint;
  for (const Json& ring : polygon) {
    if (!ring.is_array()) {
      throw FeatureDefect{"malformed geometry", "a ring must be an array of positions"};
    }
    std::vector<Eigen::Vector2d> points;
    for (const Json& position : ring) {
      if (!position.is_array() || position.size() < 2 || !position[0].is_number() ||
          !position[1].is_number() || (position.size() > 2 && !position[2].is_number())) {
        throw FeatureDefect{"malformed geometry", "a position must be 2 or 3 numbers"};
      }
      const Eigen::Vector2d point(position[0].get<double>(), position[1].get<double>());
      if (!point.allFinite()) {
        throw FeatureDefect{"non-finite vertex coordinate", ""};
      }
      if (position.size() > 2 && !footprint.z) {
        footprint.z = position[2].get<double>();
      }
      if (points.empty() || points.back() != point) {
        points.push_back(point);
      }
    }
    if (points.size() > 1 && points.front() == points.back()) {
      points.pop_back();
    }
    if (points.size() < 3) {
      throw FeatureDefect{"degenerate polygon", "a ring needs 3 distinct positions"};
    }
    footprint.rings.push_back(std::move(points));
  }
  return footprint;
}

double numberProperty(const Json& properties, const std::string& key) {
  const auto found = properties.find(key);
  if (found == properties.end() || !found->is_number()) {
    throw FeatureDefect{"missing height", fmt::format("property '{}' is not a number", key)};
  }
  const double value = found->get<double>();
  if (!std::isfinite(value)) {
    throw FeatureDefect{"non-finite attribute", key};
  }
  return value;
}

std::string featureId(const Json& feature, const FootprintOptions& options, size_t index) {
  const Json* id = nullptr;
  if (!options.id_attribute.empty() && feature.contains("properties") &&
      feature["properties"].is_object() && feature["properties"].contains(options.id_attribute)) {
    id = &feature["properties"][options.id_attribute];
  } else if (feature.contains("id")) {
    id = &feature["id"];
  }
  if (id == nullptr) {
    return fmt::format("feature-{}", index);
  }
  return id->is_string() ? id->get<std::string>() : id->dump();
}

std::vector<Building> readFeature(const Json& feature, const std::string& id,
                                  const FootprintOptions& options) {
  if (!feature.is_object() || !feature.contains("geometry") || !feature["geometry"].is_object()) {
    throw FeatureDefect{"malformed feature", "no geometry object"};
  }
  const Json& geometry = feature["geometry"];
  const std::string type = geometry.value("type", "");
  std::vector<Footprint> footprints;
  if (type == "Polygon") {
    footprints.push_back(readPolygon(geometry.value("coordinates", Json())));
  } else if (type == "MultiPolygon" && geometry.contains("coordinates") &&
             geometry["coordinates"].is_array()) {
    for (const Json& polygon : geometry["coordinates"]) {
      footprints.push_back(readPolygon(polygon));
    }
  } else {
    throw FeatureDefect{"not a footprint", fmt::format("geometry type '{}'", type)};
  }
  const Json properties = feature.contains("properties") && feature["properties"].is_object()
                              ? feature["properties"]
                              : Json::object();
  const double height_m = numberProperty(properties, options.height_attribute);
  if (height_m <= 0.0) {
    throw FeatureDefect{"missing height", fmt::format("height {} m is not positive", height_m)};
  }
  std::vector<Building> buildings;
  for (size_t part = 0; part < footprints.size(); ++part) {
    const Footprint& footprint = footprints[part];
    const double base_z = options.base_attribute.empty()
                              ? footprint.z.value_or(0.0)
                              : numberProperty(properties, options.base_attribute);
    buildings.push_back(Building{.id = footprints.size() == 1 ? id : fmt::format("{}-{}", id, part),
                                 .parent_id = {},
                                 .type = std::string("Building"),
                                 .lod = std::string("1"),
                                 .attributes_json = properties.dump(),
                                 .faces = extrudeFootprint(footprint.rings, base_z, height_m)});
  }
  return buildings;
}

std::optional<int> namedCrs(const Json& document, const std::string& source) {
  const auto crs = document.find("crs");
  if (crs == document.end()) {
    return std::nullopt;
  }
  const Json name =
      crs->is_object() && crs->contains("properties") && (*crs)["properties"].is_object()
          ? (*crs)["properties"].value("name", Json())
          : Json();
  try {
    return parseEpsgCode(name.is_string() ? name.get<std::string>() : name.dump());
  } catch (const std::invalid_argument& error) {
    throw ModelError(source, "", "unknown CRS", error.what());
  }
}

constexpr int kGeoJsonDefaultEpsg = 4326;

CityModel readDocument(std::string_view text, const std::string& source,
                       const FootprintOptions& footprint_options, const ReadOptions& options) {
  const Json document = parseJsonDocument(text, source, "", options.max_json_nesting);
  if (!document.is_object() || document.value("type", "") != "FeatureCollection" ||
      !document.contains("features") || !document["features"].is_array()) {
    throw ModelError(source, "", "malformed GeoJSON", "expected a FeatureCollection");
  }
  CityModel model;
  model.epsg = namedCrs(document, source).value_or(kGeoJsonDefaultEpsg);
  const Json& features = document["features"];
  for (size_t index = 0; index < features.size(); ++index) {
    const std::string id = features[index].is_object()
                               ? featureId(features[index], footprint_options, index)
                               : fmt::format("feature-{}", index);
    try {
      for (Building& building : readFeature(features[index], id, footprint_options)) {
        model.buildings.push_back(std::move(building));
      }
    } catch (const FeatureDefect& defect) {
      handleInvalidObject(ModelError(source, id, defect.reason, defect.detail),
                          options.invalid_objects, model.skipped);
    } catch (const Json::exception& error) {
      handleInvalidObject(ModelError(source, id, "malformed feature", error.what()),
                          options.invalid_objects, model.skipped);
    }
  }
  return model;
}

}  // namespace

std::vector<Face> extrudeFootprint(const std::vector<std::vector<Eigen::Vector2d>>& rings,
                                   double base_z, double height_m) {
  std::vector<std::vector<Eigen::Vector2d>> oriented = rings;
  for (size_t i = 0; i < oriented.size(); ++i) {
    const bool counter_clockwise = signedArea2(oriented[i]) > 0.0;
    if (counter_clockwise != (i == 0)) {
      std::reverse(oriented[i].begin(), oriented[i].end());
    }
  }
  const double top_z = base_z + height_m;
  Face roof{SurfaceKind::kRoof, {}};
  Face ground{SurfaceKind::kGround, {}};
  std::vector<Face> walls;
  for (const auto& ring : oriented) {
    roof.rings.push_back(atHeight(ring, top_z));
    std::vector<Eigen::Vector3d> reversed = atHeight(ring, base_z);
    std::reverse(reversed.begin(), reversed.end());
    ground.rings.push_back(std::move(reversed));
    // Interior on the left of each edge a->b, so the quad a b b' a' faces outwards.
    for (size_t i = 0; i < ring.size(); ++i) {
      const Eigen::Vector2d& a = ring[i];
      const Eigen::Vector2d& b = ring[(i + 1) % ring.size()];
      walls.push_back({SurfaceKind::kWall,
                       {{{a.x(), a.y(), base_z},
                         {b.x(), b.y(), base_z},
                         {b.x(), b.y(), top_z},
                         {a.x(), a.y(), top_z}}}});
    }
  }
  std::vector<Face> faces = {std::move(ground), std::move(roof)};
  faces.insert(faces.end(), std::make_move_iterator(walls.begin()),
               std::make_move_iterator(walls.end()));
  return faces;
}

CityModel readGeoJsonFootprints(std::string_view text, const std::string& source,
                                const FootprintOptions& footprint_options,
                                const ReadOptions& options) {
  try {
    return readDocument(text, source, footprint_options, options);
  } catch (const nlohmann::json::exception& error) {
    throw ModelError(source, "", "malformed GeoJSON", error.what());
  }
}

}  // namespace lineloc::citymodel
