#include "backbone/service/map_geometry.h"

namespace lineloc {

std::vector<ModelSegment> modelSegments(const std::vector<db::ModelLine>& lines,
                                        const std::vector<db::LearntLineRecord>& learnt_lines) {
  std::vector<ModelSegment> segments;
  segments.reserve(lines.size() + learnt_lines.size());
  for (const db::ModelLine& line : lines) {
    segments.push_back({line.id, static_cast<int>(line.kind), line.start_world, line.end_world});
  }
  for (const db::LearntLineRecord& line : learnt_lines) {
    segments.push_back({-line.id, static_cast<int>(citymodel::LineKind::kLearnt), line.start_world,
                        line.end_world, line.sigma_m});
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
