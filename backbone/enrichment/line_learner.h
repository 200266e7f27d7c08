// One pass's learning of lines from the frames a robot's fixes answered well
// (paper §3.1), the same for a recorded drive (lineloc-enrich) and for the
// frames a backbone answers while it serves (backbone/service/
// online_learning.h). Each frame's segments that no visible model line
// explains are placed on the model's surface (surface_observations.h) and
// associated across frames into tracks (surface_line_tracks.h), and the stored
// learnt lines it should see are noted (expected_lines.h). The pass's lines
// are its tracks that triangulate, less those of a repeating pattern
// (repeated_lines.h) and the model lines seen again (known_lines.h).
//
// Memory grows with the views its tracks keep: a track that has too few views
// to triangulate and none since a given time can be forgotten, so that a
// learner fed for hours keeps the tracks of its recent frames and those that
// have become lines.
#pragma once

#include <cstdint>
#include <vector>

#include "backbone/enrichment/expected_lines.h"
#include "backbone/enrichment/surface_line_tracks.h"
#include "backbone/enrichment/surface_observations.h"

namespace lineloc {

struct LineLearnerOptions {
  SurfaceObservationOptions observation;
  SurfaceLineTrackOptions tracks;
  ExpectedLineOptions expected;
};

// What became of the segments of the frames observed.
struct LearningCounts {
  int frames = 0;
  // Frames whose fix placed at least one segment precisely enough.
  int precise_frames = 0;
  int segments = 0;
  int explained = 0;
  int off_surface = 0;
  int shadow_edges = 0;
  int imprecise = 0;
  int on_surface = 0;
};

// A pass's learnt lines, and the stored lines it expected.
struct LearntPass {
  std::vector<LineCandidate> lines;
  std::vector<ExpectedLine> expected;
  size_t tracks = 0;
  // Triangulated lines that were model lines seen again, or of a repeating
  // pattern.
  int model_lines_seen = 0;
  int repeated_lines = 0;
};

class LineLearner {
 public:
  // `known`: the stored learnt lines the pass may be expected to see.
  LineLearner(std::vector<KnownLearntLine> known, const LineLearnerOptions& options);

  // `frame.visible` holds the model's lines only: a learnt line seen again
  // must be learnt again to count as seen.
  void observe(const EnrichmentFrame& frame, const OcclusionScene& scene);

  // Forgets the tracks with fewer views than a line needs whose last view is
  // older than `before_ns`.
  void forgetStaleTracks(int64_t before_ns);

  // Views the tracks keep.
  size_t heldViews() const;
  const LearningCounts& counts() const { return counts_; }

  // The pass's lines, none of them one of `model_lines`.
  LearntPass finish(const std::vector<ModelSegment>& model_lines) const;

 private:
  LineLearnerOptions options_;
  SurfaceLineTracks tracks_;
  ExpectedLines expected_;
  LearningCounts counts_;
};

}  // namespace lineloc
