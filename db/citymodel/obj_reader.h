// Reader of Wavefront OBJ building models: `v x y z` vertices (turned z-up
// from options.up_axis, then plus `offset`, since OBJ files carry neither CRS
// nor georeference), `f` faces (1-based or negative relative indices, `v/vt/vn`
// forms), one building per `o` object (per `g` group when the file has no
// `o`). Face kinds come from the normals of the z-up faces.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>

#include "db/citymodel/city_model.h"

namespace lineloc::citymodel {

// Throws ModelError naming `source`, the object and the line on a malformed
// statement or a vertex index out of range (unless `options` skips invalid objects).
CityModel readWavefrontObj(std::string_view text, const std::string& source,
                           const Eigen::Vector3d& offset, const ReadOptions& options);

}  // namespace lineloc::citymodel
