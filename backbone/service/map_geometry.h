// A map view's rows (db/tiles/map_tile_query.h) as visibility and matching
// take them: the model's lines and the learnt ones as segments, the faces as
// an occlusion scene with each face's building.
#pragma once

#include <vector>

#include "backbone/visibility/occlusion_scene.h"
#include "backbone/visibility/visible_lines.h"
#include "db/tiles/map_tile_query.h"

namespace lineloc {

// The model's lines, then the learnt ones (LineKind::kLearnt, their ids
// negated so that they stay apart from the model's).
std::vector<ModelSegment> modelSegments(const std::vector<db::ModelLine>& lines,
                                        const std::vector<db::LearntLineRecord>& learnt_lines = {});

OcclusionScene occlusionScene(const std::vector<db::ModelFaceRecord>& faces);

}  // namespace lineloc
