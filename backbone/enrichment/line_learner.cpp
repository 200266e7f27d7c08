#include "backbone/enrichment/line_learner.h"

#include <utility>

#include "backbone/enrichment/known_lines.h"
#include "backbone/enrichment/repeated_lines.h"

namespace lineloc {

LineLearner::LineLearner(std::vector<KnownLearntLine> known, const LineLearnerOptions& options)
    : options_(options), tracks_(options.tracks), expected_(std::move(known), options.expected) {}

void LineLearner::observe(const EnrichmentFrame& frame, const OcclusionScene& scene) {
  expected_.observe(frame, scene);
  const SurfaceObservations observed = observeSurfaceSegments(frame, scene, options_.observation);
  ++counts_.frames;
  counts_.precise_frames += observed.segments.empty() ? 0 : 1;
  counts_.segments += static_cast<int>(frame.segments.size());
  counts_.explained += observed.explained;
  counts_.off_surface += observed.off_surface;
  counts_.imprecise += observed.imprecise;
  counts_.shadow_edges += observed.shadow_edges;
  counts_.on_surface += static_cast<int>(observed.segments.size());
  for (const SurfaceSegment& segment : observed.segments) {
    tracks_.add(segment);
  }
}

void LineLearner::forgetStaleTracks(int64_t before_ns) {
  tracks_.forgetStale(before_ns);
}

size_t LineLearner::heldViews() const {
  return tracks_.viewCount();
}

LearntPass LineLearner::finish(const std::vector<ModelSegment>& model_lines) const {
  LearntPass pass;
  pass.tracks = tracks_.trackCount();
  const std::vector<LineCandidate> candidates = tracks_.candidates();
  const std::vector<LineCandidate> distinct = withoutRepeatedLines(candidates);
  pass.repeated_lines = static_cast<int>(candidates.size() - distinct.size());
  pass.lines = withoutModelLines(distinct, model_lines);
  pass.model_lines_seen = static_cast<int>(distinct.size() - pass.lines.size());
  pass.expected = expected_.expected();
  return pass;
}

}  // namespace lineloc
