// Reader of CityJSON 1.1 and 2.0 documents and of CityJSON Lines (the 3D BAG's
// streaming form: a first line with the metadata and `transform`, then one
// CityJSONFeature per line with its own vertices). Reads Building and
// BuildingPart objects at one level of detail, with their semantic surfaces
// (faces without semantics get their kind from the normal), and the terrain
// (TINRelief, CityJSON §TINRelief) as triangles; quantised vertices are
// decoded as v = scale * i + translate (CityJSON §transform).
#pragma once

#include <string>
#include <string_view>

#include "db/citymodel/city_model.h"

namespace lineloc::citymodel {

// `source` names the input in error messages. Throws ModelError on malformed
// JSON, a missing or broken `vertices` or `transform`, an unknown CRS, or an
// object with bad geometry (vertex index out of range, wrong nesting) unless
// `options` skips invalid objects.
CityModel readCityJson(std::string_view text, const std::string& source,
                       const ReadOptions& options);

CityModel readCityJsonLines(std::string_view text, const std::string& source,
                            const ReadOptions& options);

}  // namespace lineloc::citymodel
