// One robot as the backbone serves it, and the policy that decides how each
// of its frames is answered. It needs no database and no DDS: its caller
// hands it each frame with the map around it, runs its searches on a worker
// and publishes what it answers.
//
// A frame's prior is the robot's prediction, its height replaced by the
// model's ground level there plus the robot's stated camera height (sigma
// ground_level_sigma_m) whenever the prediction's is poorer, and widened
// while the robot is searched for again (tracking_proof.h). Then:
//  - a prior narrow enough to track from (needsAcquisition, localizer.h) is
//    tracked;
//  - else a hypothesis the acquisition took, while it is carried
//    (TrackingProof::carriedStart), is tracked from, probing
//    carried_start_step_m along the horizontal axes
//    (LocalizerOptions::min_start_step_m);
//  - else the frame is searched (acquisition_session.h): the robot's searches
//    form one sequential estimator over its frames, moved between them by
//    the robot's own motion O (its predictions without their DGPS jumps,
//    predicted_motion.h), until one hypothesis is taken and tracking starts
//    from it.
// A tracked OK answer's covariance is raised to the sample covariance of the
// robot's answers of the last second, each moved to its frame by the robot's
// motion (fix_scatter.h), and carries the part of it tracking has not proven
// yet (tracking_proof.h), whose proof searches the session asks for.
//
// A robot taken over from another backbone is offered that backbone's
// newest handover at each frame until its tracking is proven here; an OK fix
// continues the proof from it when the rule of tracking_proof.h allows, and
// a robot that backbone was still searching for carries its hypotheses into
// the search here (acquisition_session.h). Every frame answered states the
// handover this backbone leaves: the proof, or while the robot is searched
// for, the acquisition's hypotheses.
//
// Threads: frames (hear, planFor, answer, awaitsHandover, handover,
// positionAhead) come one at a time, in order (frame_workers.h), and prior
// beside them from the exposure notices' thread; searches and proofs on
// another, one at a time per robot; the tracking proof they share, and the
// handover offered (from any thread), are locked.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "backbone/matching/localizer.h"
#include "backbone/service/acquisition_session.h"
#include "backbone/service/fix_scatter.h"
#include "backbone/service/predicted_motion.h"
#include "backbone/service/prepared_maps.h"
#include "backbone/service/tracking_proof.h"
#include "common/messages/messages.h"

namespace lineloc {

struct RobotSessionOptions {
  double ground_level_sigma_m = 0.1;
  // Tracking from a taken hypothesis probes this far along the horizontal
  // axes (LocalizerOptions::min_start_step_m).
  double carried_start_step_m = 0.5;
  PredictedMotionOptions motion;
  FixScatterOptions fix_scatter;
  // The acquisition's estimator over the robot's searched frames.
  HypothesisSetOptions hypotheses;
  TrackingProofOptions proof;
};

// The PoseFix status that states an alignment's outcome.
lineloc_msg_FixStatus toFixStatus(AlignmentStatus status);

class RobotSession {
 public:
  // `localizer`: the limits of tracking and the acquisition's settings.
  RobotSession(const RobotSessionOptions& options, const LocalizerOptions& localizer);

  // The robot's odometry at `line_set`'s frame; called once per frame, in
  // order.
  OdometryPose hear(const LineSetData& line_set);

  // The prior of `line_set`'s frame in `map` (see above).
  PoseWithCovariance prior(const LineSetData& line_set, const PreparedMap& map) const;

  enum class Plan { kTrack, kSearch };
  struct FramePlan {
    Plan plan = Plan::kSearch;
    // What the frame is tracked from, or searched around.
    PoseWithCovariance prior;
    // Tracking from a carried hypothesis: LocalizerOptions::min_start_step_m.
    double min_start_step_m = 0.0;
  };
  FramePlan planFor(const LineSetData& line_set, const OdometryPose& odometry,
                    const PreparedMap& map) const;

  // Fills `fix` from the localization of a tracked frame; an OK one gets the
  // floor of the robot's recent answers and its unproven part. Returns the
  // proof search due, if one is.
  struct Answered {
    std::optional<ProofRequest> proof_due;
    // Whether this frame started tracking from the robot's own prediction,
    // or continued it from the handover offered.
    bool started_from_prediction = false;
    bool resumed = false;
  };
  Answered answer(const LineSetData& line_set, const OdometryPose& odometry,
                  const Localization& localization, PoseFixData& fix);

  // Searches the frame around `prior` and starts tracking when a hypothesis
  // is taken.
  AcquisitionSession::Searched search(const LineSetData& line_set, const OdometryPose& odometry,
                                      std::shared_ptr<const PreparedMap> map,
                                      const PoseWithCovariance& prior,
                                      const LocalizerOptions& options);

  // Searches around `tracked`, the frame's tracked pose, as `request` asked,
  // and proves or ends that tracking.
  struct Proved {
    Localization localization;
    ProofVerdict verdict;
    // False when the robot no longer tracks from the start it judged.
    bool applied = false;
  };
  Proved prove(const LineSetData& line_set, const PreparedMap& map,
               const Eigen::Isometry3d& tracked, const ProofRequest& request,
               const LocalizerOptions& options);

  // Whether tracking is not proven here yet, and so whether a handover from
  // another backbone could add to it (offerHandover).
  bool awaitsHandover() const;
  // The handover from another backbone, in place of any offered before; the
  // robot's next OK fix here takes it or leaves it.
  void offerHandover(const TrackingHandover& handover);
  // What a backbone taking the robot over at the frame of (`stamp_ns`,
  // `odometry`) continues from.
  TrackingHandover handover(int64_t stamp_ns, const OdometryPose& odometry) const;

  // Where the robot will be `lookahead_s` after `line_set`'s frame at the
  // speed between its last two frames; nullopt for its first.
  std::optional<Eigen::Vector3d> positionAhead(const LineSetData& line_set, double lookahead_s);

 private:
  PoseWithCovariance groundedPrior(const LineSetData& line_set, const PreparedMap& map) const;

  RobotSessionOptions options_;
  LocalizerOptions localizer_;
  // The frames' thread's own.
  PredictedMotion motion_;
  FixScatter fix_scatter_;
  struct StampedPosition {
    int64_t stamp_ns = 0;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
  };
  std::optional<StampedPosition> last_position_;
  // The searches' own, but for its handed and adopted hypotheses.
  AcquisitionSession acquisition_;
  mutable std::mutex proof_mutex_;
  TrackingProof proof_;
  std::optional<TrackingHandover> offered_handover_;  // under proof_mutex_
};

}  // namespace lineloc
