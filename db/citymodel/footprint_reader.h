// Building footprints in GeoJSON (Polygon or MultiPolygon features with a
// height attribute), extruded to LoD1 blocks: a ground face, a flat roof at
// base + height, and one vertical wall per footprint edge (holes included).
// The CRS is the one named by the legacy `crs` member, else WGS84 (EPSG:4326)
// as RFC 7946 prescribes.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "db/citymodel/city_model.h"

namespace lineloc::citymodel {

struct FootprintOptions {
  std::string height_attribute = "height";  // metres above the base, > 0
  std::string base_attribute;               // base height property; empty: the footprint's z, or 0
  std::string id_attribute;  // feature id property; empty: the feature's `id`, or its index
};

// Throws ModelError naming `source` and the feature on malformed JSON, missing
// or non-positive height, or bad coordinates (unless `options` skips invalid objects).
CityModel readGeoJsonFootprints(std::string_view text, const std::string& source,
                                const FootprintOptions& footprint_options,
                                const ReadOptions& options);

// The LoD1 block over a footprint: rings[0] the exterior, the rest holes, in
// any orientation (they are reoriented: exterior counter-clockwise seen from
// above, so every face normal points out of the block).
std::vector<Face> extrudeFootprint(const std::vector<std::vector<Eigen::Vector2d>>& rings,
                                   double base_z, double height_m);

}  // namespace lineloc::citymodel
