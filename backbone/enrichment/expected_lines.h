// Which known learnt lines a pass's frames should have seen, so that a line
// that is no longer there (a shop sign taken down, scaffolding gone) can be
// retired (db/enrichment_store.h).
//
// A frame expects a line when its pose places the line's middle on its wall
// to within max_placement_sigma_m across it (posePlacementSigma, as a
// segment must to be learnt from), the middle lies in front of the camera
// within max_depth_m and no face stands between them, and the line projects
// into the image at least min_length_px long. A pass expects the line when at
// least min_frames of its frames did: a few frames may miss a line that is
// there (a passing van), many may not.
#pragma once

#include <cstdint>
#include <vector>

#include "backbone/enrichment/surface_observations.h"

namespace lineloc {

struct KnownLearntLine {
  int64_t id = 0;
  Eigen::Vector3d start_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_world = Eigen::Vector3d::Zero();
  Plane plane;
};

struct ExpectedLineOptions {
  double max_placement_sigma_m = 0.03;
  double max_depth_m = 20.0;
  double min_length_px = 15.0;
  int min_frames = 10;
};

// A line the pass expected, and the last frame's time that expected it.
struct ExpectedLine {
  int64_t id = 0;
  int64_t expected_at_ns = 0;
};

class ExpectedLines {
 public:
  ExpectedLines(std::vector<KnownLearntLine> lines, const ExpectedLineOptions& options);

  void observe(const EnrichmentFrame& frame, const OcclusionScene& scene);

  // The lines at least min_frames frames expected, in the order given.
  std::vector<ExpectedLine> expected() const;

 private:
  bool expects(const EnrichmentFrame& frame, const OcclusionScene& scene,
               const KnownLearntLine& line) const;

  std::vector<KnownLearntLine> lines_;
  ExpectedLineOptions options_;
  std::vector<int> frames_;
  std::vector<int64_t> last_ns_;
};

}  // namespace lineloc
