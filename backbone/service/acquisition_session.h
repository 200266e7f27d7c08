// A robot's acquisition: the frames the backbone searches for its camera,
// each searched with the hypotheses of the frames before it carried in, and
// weighed with them (hypothesis_set.h), until one hypothesis is taken. The
// session keeps what the window's frames need to score a hypothesis found
// later in them: their image segments, camera, prior and map. It needs no
// database and no DDS: a caller hands it each frame with the map around it.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "backbone/matching/localizer.h"
#include "backbone/service/hypothesis_set.h"
#include "backbone/service/prepared_maps.h"
#include "common/messages/messages.h"

namespace lineloc {

class AcquisitionSession {
 public:
  explicit AcquisitionSession(const HypothesisSetOptions& options = {});

  struct Searched {
    // The frame's own search: its best pose and summary, for the log.
    Acquisition acquisition;
    // The hypothesis taken, if one is; else why not, for the log.
    std::optional<HypothesisDecision> decision;
    std::string undecided;
    size_t hypotheses = 0;
  };

  // Searches `line_set`'s frame around `prior` (too wide to track from) in
  // `map`, with the hypotheses carried in, and weighs it in.
  Searched search(const LineSetData& line_set, const OdometryPose& odometry,
                  std::shared_ptr<const PreparedMap> map, const PoseWithCovariance& prior,
                  const LocalizerOptions& options);

  // Forgets the frames and hypotheses: the robot is tracked, or starts again.
  void clear();

 private:
  struct Frame {
    std::vector<ImageSegment> segments;
    PinholeCamera camera;
    PoseWithCovariance prior;
    std::shared_ptr<const PreparedMap> map;
  };

  HypothesisSet hypotheses_;
  std::map<uint64_t, Frame> frames_;
  uint64_t next_frame_id_ = 0;
};

}  // namespace lineloc
