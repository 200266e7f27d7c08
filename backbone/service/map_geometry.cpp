#include "backbone/service/map_geometry.h"

namespace lineloc {

std::vector<ModelSegment> modelSegments(const std::vector<db::ModelLine>& lines) {
  std::vector<ModelSegment> segments;
  segments.reserve(lines.size());
  for (const db::ModelLine& line : lines) {
    segments.push_back({line.id, static_cast<int>(line.kind), line.start_world, line.end_world});
  }
  return segments;
}

OcclusionScene occlusionScene(const std::vector<db::ModelFaceRecord>& faces) {
  std::vector<FaceRing> rings;
  std::vector<int64_t> building_ids;
  rings.reserve(faces.size());
  building_ids.reserve(faces.size());
  for (const db::ModelFaceRecord& face : faces) {
    rings.push_back(face.ring_world);
    building_ids.push_back(face.building_id);
  }
  return OcclusionScene(rings, building_ids);
}

}  // namespace lineloc
