// Whether a robot's tracking can be trusted yet (paper §3.2: "a false match
// gives a precise but wrong pose"). A pose the acquisition took can lie in a
// neighbouring basin, which tracking then follows, and tracking's covariance,
// from one view's residuals, cannot tell. So until tracking is proven, every
// OK fix states an unproven part U (PoseFix::unproven_*: one offset the fixes
// share, which the robot fuses as one, correlated_fix_model.h) and carries it
// in its covariance:
//   U = max(acquired_*_sigma, R, P),
// the search's resolution (pose_acquisition.h), the farthest rival R still
// held, and, until a proof search has aligned around tracking, that search's
// own reach P (proof_position_sigma_m, confirm_rotation_rad).
//
// Starts. Tracking starts from a pose the acquisition took (its rivals, and
// its own sigmas when it is too wide to track from, make R), which the
// robot's next frames for carry_search_s are tracked from, A O_A^-1 O with O
// the robot's odometry; or from the first frame a robot is tracked from its
// own prediction (a restarted backbone, a robot forgotten and back, a new
// odometry epoch), which is proven alike.
//
// Proof searches run over proof_position_sigma_m around a frame's tracked
// pose: the first at once, the next once the robot has moved
// acquisition_proven_after_m from the start, then every proof_retry_m.
// agreeing_proofs_needed of them from elsewhere that agree (within
// confirm_position_m and confirm_rotation_rad) prove tracking. A pose
// elsewhere scoring at least ambiguous_score_fraction of the tracked pose
// (verificationScore) is a rival R grows to cover; one the tracked pose scores
// below that fraction of ends tracking, and the robot is searched for again
// over at least proof_position_sigma_m. A verdict on a start the robot no
// longer tracks from is dropped.
//
// Handover. A backbone that takes a robot over from another (several
// backbones, backbone_peers.h) continues the proof the other published at a
// frame it answered (TrackingHandover: its agreeing proofs, rival, and the
// motion left until the next proof search), instead of proving tracking from
// the start. It does so at an OK fix of its own that is newer than the
// handover, while the handover states more agreeing proofs than tracking has
// here (none when the robot has no start here), when the robot's prediction
// at that fix is narrow (position sigma at most confirm_position_m / 3,
// rotation sigma at most confirm_rotation_rad / 3 per axis) and agrees with
// the fix: the robot's filter fused the handed-over fixes with their own
// unproven part, so a narrow prediction is in their basin, and dead
// reckoning since cannot have left it. Otherwise tracking goes on as above.
//
// Not thread-safe: its owner serialises the frames' and the proof searches'
// calls, but for proofPrior and agreement, which read its options only.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "backbone/matching/localizer.h"
#include "backbone/service/hypothesis_set.h"
#include "backbone/service/predicted_motion.h"
#include "backbone/service/prepared_maps.h"
#include "common/messages/messages.h"

namespace lineloc {

struct TrackingProofOptions {
  // A proof search's pose within both of these of the tracked one agrees with it.
  double confirm_position_m = 0.3;
  double confirm_rotation_rad = 0.5 * M_PI / 180.0;
  // A taken hypothesis starts tracking for this long after its frame.
  double carry_search_s = 1.0;
  // Proof searches run over this sigma around the tracked pose (three sigma:
  // a few windows' widths), the first at once, each next one due
  // proof_retry_m further on, and acquisition_proven_after_m on at least.
  double acquisition_proven_after_m = 1.0;
  double proof_position_sigma_m = 0.5;
  double proof_retry_m = 1.0;
  // Agreeing proof searches from elsewhere that prove tracking.
  int agreeing_proofs_needed = 2;
};

// Where tracking started: a pose found at a frame (by a search, or tracked
// from the robot's prediction) and the robot's odometry there.
struct TrackingOrigin {
  int64_t stamp_ns = 0;
  PoseWithCovariance T_world_camera_found;
  OdometryPose odometry;
  bool operator==(const TrackingOrigin& other) const {
    return stamp_ns == other.stamp_ns && odometry.epoch == other.odometry.epoch;
  }
};

// A robot's proof as the backbone that tracked it left it at its OK fix of
// `stamp_ns` (see Handover above).
struct TrackingHandover {
  int64_t stamp_ns = 0;
  // False when the robot was not tracked there (not yet, or searched for
  // again): nothing to continue.
  bool tracking = false;
  int agreeing_proofs = 0;
  // The robot's motion (m) left until the next proof search is due.
  double proof_due_in_m = 0.0;
  PoseOffset rival = {};
  bool looked_around = false;
  // The acquisition's hypotheses after its last search, at its frame's
  // stamp, while the robot is searched for (AcquisitionSession::handed).
  HandedHypotheses hypotheses = {};
};

// A proof search due at a tracked frame: `moved_m` from `origin`'s viewpoint.
struct ProofRequest {
  TrackingOrigin origin;
  double moved_m = 0.0;
};

enum class Proof { kAgrees, kUndecided, kContradicts };

struct ProofVerdict {
  Proof proof = Proof::kUndecided;
  // For the log.
  std::string outcome;
  // An undecided proof's farthest rival of the tracked pose.
  PoseOffset rival = {};
  // Whether the proof search aligned around tracking (OK or ambiguous).
  bool looked_around = false;
};

// What the poses a proof search `found` around `tracked` (the frame's tracked
// pose) say of tracking: an OK pose elsewhere contradicts it only when the
// tracked pose scores below ambiguous_score_fraction of it (verificationScore,
// pose_acquisition.h). A pose elsewhere, OK or either of an ambiguous
// search's two, that scores at least that fraction of the tracked pose is its
// rival: the view does not tell them apart.
ProofVerdict judgeProof(const LineSetData& line_set, const PreparedMap& map,
                        const Eigen::Isometry3d& tracked, const Localization& found,
                        const AcquisitionOptions& acquisition, const PoseOffset& agreement);

class TrackingProof {
 public:
  TrackingProof(const TrackingProofOptions& options, const LocalizerOptions& localizer);

  // Tracking starts from the hypothesis `decision` took at the frame of
  // `stamp_ns`; a robot searched for again is no longer.
  void startFromSearch(int64_t stamp_ns, const OdometryPose& odometry,
                       const HypothesisDecision& decision);

  // The taken hypothesis moved to the frame at (`stamp_ns`, `odometry`) and
  // narrowed to the tracking limits (narrowedForTracking), while it is carried.
  std::optional<PoseWithCovariance> carriedStart(int64_t stamp_ns,
                                                 const OdometryPose& odometry) const;

  // `prior` widened to proof_position_sigma_m horizontally at least, while
  // the robot is searched for again after a proof ended its tracking.
  PoseWithCovariance searchPrior(const PoseWithCovariance& prior) const;

  struct Unproven {
    // U above (standard deviations); nullopt once tracking is proven.
    std::optional<PoseOffset> offset;
    std::optional<ProofRequest> proof_due;
    // Whether this frame started tracking from the robot's own prediction.
    bool started_from_prediction = false;
  };
  // What an OK fix `T_world_camera_fixed` at (`stamp_ns`, `odometry`) leaves
  // unproven; a robot with no start, or one of another odometry epoch, starts
  // here.
  Unproven unprovenAt(int64_t stamp_ns, const OdometryPose& odometry,
                      const PoseWithCovariance& T_world_camera_fixed);

  // Whether tracking is proven here, so that no handover adds to it.
  bool proven() const;

  // Continues tracking from `handover` at the OK fix `T_world_camera_fixed`
  // of (`stamp_ns`, `odometry`), whose prediction was
  // `T_world_camera_predicted`, when the rule above allows it; true when it
  // did. The caller then asks unprovenAt for the same fix.
  bool resume(const TrackingHandover& handover, int64_t stamp_ns, const OdometryPose& odometry,
              const PoseWithCovariance& T_world_camera_fixed,
              const PoseWithCovariance& T_world_camera_predicted);

  // The proof as it stands at the frame of (`stamp_ns`, `odometry`), for a
  // backbone that takes the robot over: not tracking while the robot has no
  // start of that epoch.
  TrackingHandover handover(int64_t stamp_ns, const OdometryPose& odometry) const;

  // Applies the verdict of a proof search requested at `request`; false,
  // changing nothing, when the robot no longer tracks from the start it judged.
  bool apply(const ProofVerdict& verdict, const ProofRequest& request);

  // The proof search's prior around a tracked pose.
  PoseWithCovariance proofPrior(const Eigen::Isometry3d& tracked, double ground_sigma_m) const;

  // Two poses agree within this: confirm_position_m and confirm_rotation_rad.
  PoseOffset agreement() const;

 private:
  struct Start {
    TrackingOrigin origin;
    // Found by a search, and so carried (carriedStart).
    bool searched = false;
    int agreeing_proofs = 0;
    // Motion from the origin's viewpoint (m) at which a proof search is due.
    double proof_due_m = 0.0;
    PoseOffset rival = {};
    bool looked_around = false;
  };

  TrackingProofOptions options_;
  LocalizerOptions localizer_;
  // The robot's motion (m) from `start`'s viewpoint to `odometry`.
  static double movedFrom(const Start& start, const OdometryPose& odometry);

  std::optional<Start> start_;
  bool searching_again_ = false;
};

}  // namespace lineloc
