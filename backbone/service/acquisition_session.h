// A robot's acquisition: the frames the backbone searches for its camera,
// each searched with the hypotheses of the frames before it carried in, and
// weighed with them (hypothesis_set.h), until one hypothesis is taken. The
// session keeps what the window's frames need to score a hypothesis found
// later in them: their image segments, camera, prior and map. It needs no
// database and no DDS: a caller hands it each frame with the map around it.
//
// A backbone that takes the robot over from another carries the other's
// hypotheses (HandedHypotheses) into its first search as starts, moved to
// that frame's predicted pose: the robot's motion between the two frames as
// its predictions give it, a DGPS correction between them included. They
// join the estimator as hypotheses the robot's motion carried, not as grid
// proposals and with no evidence of their own (hypothesis_set.h), so that
// the decision still rests on what this backbone's searches see; handed
// hypotheses older than window_s are not carried.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
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

  // The hypotheses after the last search (none before the first, or once
  // cleared), for a backbone that takes the robot over. Safe to call beside
  // search().
  HandedHypotheses handed() const;
  // Another backbone's hypotheses of the robot (its handed()), carried into
  // the next search when this session holds none of its own (see above), in
  // place of any adopted before. Safe to call beside search().
  void adopt(HandedHypotheses hypotheses);

 private:
  // The adopted hypotheses as starts in `line_set`'s frame, when they are
  // to be carried into it (see above); taken once.
  std::vector<Eigen::Isometry3d> adoptedStarts(const LineSetData& line_set);

  struct Frame {
    std::vector<ImageSegment> segments;
    PinholeCamera camera;
    PoseWithCovariance prior;
    std::shared_ptr<const PreparedMap> map;
    double sky_clutter_density = 0.0;
  };

  const int64_t window_ns_;
  HypothesisSet hypotheses_;
  std::map<uint64_t, Frame> frames_;
  uint64_t next_frame_id_ = 0;
  mutable std::mutex handed_mutex_;
  HandedHypotheses handed_;                  // under handed_mutex_
  std::optional<HandedHypotheses> adopted_;  // under handed_mutex_
};

}  // namespace lineloc
