// A map view's rows (db/tiles/map_tile_query.h) as visibility and matching
// take them: the model lines as segments, the faces as an occlusion scene
// with each face's building.
#pragma once

#include <vector>

#include "backbone/visibility/occlusion_scene.h"
#include "backbone/visibility/visible_lines.h"
#include "db/tiles/map_tile_query.h"

namespace lineloc {

std::vector<ModelSegment> modelSegments(const std::vector<db::ModelLine>& lines);

OcclusionScene occlusionScene(const std::vector<db::ModelFaceRecord>& faces);

}  // namespace lineloc
