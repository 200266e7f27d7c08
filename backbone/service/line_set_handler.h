// Turns one received LineSet into its PoseFix (paper §3.2): validate it, take
// the model lines and faces near the predicted pose from the prepared map,
// localize the camera in them (localizer.h) and answer with the aligned pose
// and its covariance, or with a status that says why no pose can be trusted.
// Malformed input is dropped and counted; a map failure is answered with
// FIX_INTERNAL_ERROR and counted; serving goes on.
//
// Ground. A robot that states its camera height above the ground has its
// predicted height replaced by the model's ground level there plus that
// height (sigma ground_level_sigma_m) whenever its own is poorer.
//
// Maps. What localization needs of a map view is built once per view, off
// the frames' path (prepared_maps.h); a frame with no map prepared near it
// yet is answered with FIX_NO_MATCH_COMPUTED. The tiles around where a robot
// will be prefetch_lookahead_s later are queued for loading.
//
// Acquisition. A frame whose prediction is too poor to track starts a search
// on the SearchWorker thread (search_worker.h), unless the robot's last one
// still runs, and is answered at once with FIX_NO_MATCH_COMPUTED: no LineSet
// waits for a search. The robot's searches form one sequential estimator
// (acquisition_session.h, hypothesis_set.h): the poses they align are kept
// as hypotheses, moved between frames by the robot's own motion O (read from
// its predictions without their DGPS jumps, predicted_motion.h), aligned
// again in each searched frame and weighed over a window of views, until one
// is likely enough to take. The robot's next frames are then tracked from it,
// A O_A^-1 O, for carry_search_s, with carried_start_step_m probes along the
// horizontal axes (LocalizerOptions::min_start_step_m).
//
// Proof. A taken pose can lie in a neighbouring basin, which tracking then
// follows, and tracking's covariance, from one view's residuals, cannot tell.
// So every OK fix states an unproven part (PoseFix::unproven_*: one offset
// the fixes share, which the robot fuses as one, inertial_navigator.h) and
// carries it in its covariance: the search's resolution (acquired_*_sigma,
// pose_acquisition.h), the farthest rival the acquisition still held, and
// until a proof search has aligned around tracking that search's own reach
// (proof_position_sigma_m, confirm_rotation_rad). Proof searches run over
// proof_position_sigma_m around the frame's tracked pose: the first at once,
// the next once the robot has moved acquisition_proven_after_m from the
// tracking start, then every proof_retry_m. agreeing_proofs_needed of them
// from elsewhere that agree (within confirm_position_m and
// confirm_rotation_rad) prove tracking, and the unproven part goes. A pose
// elsewhere scoring at least ambiguous_score_fraction of the tracked pose
// (verificationScore, pose_acquisition.h) is a rival the unproven part grows
// to cover; one the tracked pose scores below that fraction of ends tracking,
// and the robot is searched for again over at least proof_position_sigma_m.
// A verdict on a tracking start the robot no longer tracks from is dropped.
// A robot tracked from its own prediction (a restarted backbone, a robot
// forgotten and back, or a new odometry chain) is proven alike from its first
// tracked frame.
//
// Covariance. A tracked answer's covariance is raised to the sample
// covariance of the robot's answers of the last second, each moved to its
// frame by the robot's motion (fix_scatter.h).
//
// Exposure notices. A robot may send each frame's LineSet without its
// features at the frame's exposure (ExposureTopic, common/messages/topics.h).
// When its prediction is one to track in a map already prepared, the
// hidden-line removal from it (visibleFromPrior, localizer.h) runs at once on
// exposure_visibility_threads while the robot extracts its lines, and the
// LineSet that follows takes it when its prior, map view and camera are the
// ones it was computed for. A notice that comes after its LineSet, or after a
// later one, is skipped and counted. Notices wait for their LineSets in
// order, up to kMaxWaitingNotices per robot.
//
// Forgetting. A robot not heard from for forget_robot_after_s is forgotten
// (its motion, answers, searches, proofs, notices and cadence), so that a
// backbone serving robots that come and go holds only the ones it serves; one
// that comes back is served as after a backbone restart. The sweep runs on the
// LineSets' thread, at most every forget_robot_after_s / 2.
//
// Background work. Searches and map preparation pause between pieces while
// a LineSet is being handled and from quiet_before_frame_ms before a tracked
// robot's next one is due (foreground_gate.h, frame_cadence.h).
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "backbone/map/map_tile_cache.h"
#include "backbone/matching/localizer.h"
#include "backbone/service/acquisition_session.h"
#include "backbone/service/fix_scatter.h"
#include "backbone/service/frame_cadence.h"
#include "backbone/service/predicted_motion.h"
#include "backbone/service/prepared_maps.h"
#include "backbone/service/search_worker.h"
#include "common/geodesy/site_sun.h"
#include "common/messages/message_validator.h"
#include "common/messages/messages.h"
#include "common/parallel/foreground_gate.h"

namespace lineloc {

struct BackboneCounters {
  uint64_t received = 0;
  uint64_t answered = 0;
  uint64_t dropped_invalid = 0;
  uint64_t map_errors = 0;
  uint64_t fixes_ok = 0;
  uint64_t searches = 0;
  // Tracked frames whose hidden lines were removed from their exposure notice.
  uint64_t visibility_ahead = 0;
  // Exposure notices skipped because their LineSet, or a later one, came first.
  uint64_t notices_after_line_set = 0;
  // Robots heard from within forget_robot_after_s, and those forgotten since start.
  uint64_t robots = 0;
  uint64_t robots_forgotten = 0;
  std::string last_drop_reason;
  // Stage times of the last kTimingWindow answers, oldest overwritten first.
  std::vector<StageTimingsNs> recent_timings;
};

inline constexpr size_t kTimingWindow = 4096;

struct PipelineOptions {
  double query_radius_m = 150.0;
  // A frame whose own view is still being prepared is localized in a view
  // asked for this close to it (PreparedMaps).
  double map_reuse_distance_m = 50.0;
  double prefetch_lookahead_s = 3.0;
  double ground_level_sigma_m = 0.1;
  // A proof search's pose within both of these of the tracked one agrees with it.
  double confirm_position_m = 0.3;
  double confirm_rotation_rad = 0.5 * M_PI / 180.0;
  // The acquisition's estimator over the robot's searched frames.
  HypothesisSetOptions hypotheses;
  // A taken hypothesis starts tracking for this long after its frame.
  double carry_search_s = 1.0;
  // Tracking from a taken hypothesis probes this far along the horizontal
  // axes (LocalizerOptions::min_start_step_m).
  double carried_start_step_m = 0.5;
  // Fixes keep the acquired pose's resolution term until proof searches
  // from at least this far from where the confirmed search saw the robot
  // agree with tracking; over this sigma around the tracked pose (three
  // sigma: a few windows' widths), the first at once, each next one due
  // proof_retry_m further on, and acquisition_proven_after_m on at least.
  double acquisition_proven_after_m = 1.0;
  double proof_position_sigma_m = 0.5;
  double proof_retry_m = 1.0;
  // Agreeing proof searches, each proof_retry_m on from the one before, that
  // prove tracking.
  int agreeing_proofs_needed = 2;
  // An answer slower than this (a frame period at 30 Hz) is logged with its
  // stage times.
  double slow_answer_ms = 33.0;
  // Searches and map preparation step aside while a frame is being answered
  // and from this long before a tracked robot's next frame is due to arrive
  // (foreground_gate.h), each time for at most max_background_yield_ms.
  double quiet_before_frame_ms = 8.0;
  double max_background_yield_ms = 33.0;
  // Threads of the hidden-line removal started at a frame's exposure: one,
  // so that a robot on the same machine keeps a core for its line extraction.
  int exposure_visibility_threads = 1;
  // A robot not heard from for this long is forgotten (see above); one whose
  // radio drops out for seconds keeps its state.
  double forget_robot_after_s = 30.0;
  PredictedMotionOptions motion;
  FixScatterOptions fix_scatter;
  LocalizerOptions localizer;
  // When set, each LineSet is localized under the sun of its stamp instead
  // of localizer.visibility.sunlight (none while the sun is down).
  std::optional<SiteSun> sun_from_clock;
};

// The sun a LineSet taken at `stamp_ns` is localized under: the clock's when
// options.sun_from_clock is set (none while it is down), else the localizer's.
std::optional<Sunlight> sunlightAt(const PipelineOptions& options, int64_t stamp_ns);

class LineSetHandler {
 public:
  LineSetHandler(MapTileCache& map, const MessageLimits& limits, const PipelineOptions& options);

  // The fix to publish, or nullopt when the message was dropped.
  std::optional<PoseFixData> handle(const lineloc_msg_LineSet& message);

  // A frame's exposure notice (see above); a malformed one is dropped and
  // counted. Safe to call beside handle().
  void handleExposure(const lineloc_msg_LineSet& message);

  // Forgets the robots not heard from for forget_robot_after_s before
  // `now_ns` (steady clock). Call both from the thread that calls handle();
  // handle() calls the second itself (see above).
  void forgetSilentRobots(int64_t now_ns);
  // The same, unless a sweep ran within forget_robot_after_s / 2.
  void forgetSilentRobotsWhenDue(int64_t now_ns);

  // Blocks until the searches under way have finished.
  void waitForSearches();

  BackboneCounters counters() const;

 private:
  // Records that `robot_id`'s LineSet arrived at `arrival_ns` (steady
  // clock), first forgetting the silent robots when that is due: itself too
  // when it was one.
  void hearFrom(const std::string& robot_id, int64_t arrival_ns);
  // Drops every table's entries of robots not in last_heard_ns_: also those a
  // search that finished after its robot was forgotten wrote.
  void forgetUnheardRobots();
  void prefetchAlongMotion(const LineSetData& line_set);
  // The localizer's options for `line_set`: under sunlightAt its stamp.
  LocalizerOptions localizerOptions(const LineSetData& line_set) const;
  // Tracks `line_set` from `prior` into `fix`; an OK answer gets the floor of
  // the robot's recent answers (fix_scatter.h) and is widened until proven.
  // `visible_from_prior`, when given, is the hidden-line removal for it.
  void track(const LineSetData& line_set, const OdometryPose& odometry,
             const std::shared_ptr<const PreparedMap>& map, const PoseWithCovariance& prior,
             const LocalizerOptions& options, PoseFixData& fix,
             const std::vector<VisibleSegment>* visible_from_prior = nullptr);
  // Runs on the search worker: the robot's acquisition session searches the
  // frame (`odometry` is its) and, when it takes a hypothesis, tracking starts.
  void search(const LineSetData& line_set, const OdometryPose& odometry,
              std::shared_ptr<const PreparedMap> map, const PoseWithCovariance& prior);
  // Starts the robot's tracking from the hypothesis `decision` took at
  // `line_set`'s frame, its rivals and, when it is too wide to track from,
  // its own sigmas left unproven.
  void startTrackingFrom(const LineSetData& line_set, const OdometryPose& odometry,
                         const HypothesisDecision& decision);
  PoseWithCovariance groundedPrior(const LineSetData& line_set, const PreparedMap& map) const;
  // The prior a frame of `line_set`'s robot is tracked from in `map` unless a
  // taken hypothesis is carried: the prediction grounded and, for a robot
  // searched for again, widened (searchPrior).
  PoseWithCovariance trackingPrior(const LineSetData& line_set, const PreparedMap& map);
  // A frame of one robot: its sequence number and exposure stamp.
  struct FrameId {
    uint32_t sequence_number = 0;
    int64_t stamp_ns = 0;
    bool operator==(const FrameId&) const = default;
  };
  // The hidden-line removal started at a frame's exposure, for its LineSet.
  struct Notice {
    FrameId frame;
    std::shared_ptr<const PreparedMap> map;
    PoseWithCovariance prior;
    PinholeCamera camera;
    std::shared_future<std::vector<VisibleSegment>> visible;
  };
  // Queues `notice` for its LineSet; false, queueing nothing, when that
  // LineSet or a later one has come already.
  bool aheadOfLineSet(const std::string& robot_id, Notice notice);
  // Takes `line_set`'s notice out of its robot's queue, with those of older
  // frames, whose LineSets will not come; later frames' notices stay.
  std::optional<Notice> takeNotice(const LineSetData& line_set);
  // The hidden-line removal `notice` started, when it was for this frame's
  // prior, map and camera.
  std::optional<std::vector<VisibleSegment>> visibilityAhead(
      const LineSetData& line_set, std::optional<Notice> notice,
      const std::shared_ptr<const PreparedMap>& map, const PoseWithCovariance& prior);
  // Counts a malformed message and logs `kind`'s drop.
  void countDrop(const char* kind, uint32_t sequence_number, const std::string& error);
  // The robot's taken hypothesis moved to `line_set`'s time and narrowed to
  // the tracking limits (narrowedForTracking), when there is one to carry.
  std::optional<PoseWithCovariance> carriedSearch(const LineSetData& line_set,
                                                  const OdometryPose& odometry);
  // Adds an acquired pose's resolution term (acquired_*_sigma,
  // pose_acquisition.h), or the farthest rival, or before any proof search
  // has aligned around tracking the proof search's own prior sigmas, to an
  // OK fix's covariance until proof searches have agreed with tracking,
  // stating it as the fix's unproven part (one offset the robot's fixes
  // share until then), and submits the next proof search when it is due. A
  // robot with no tracking start, or one of another odometry epoch, has it
  // set at `fix`.
  void widenUntilProven(const LineSetData& line_set, const OdometryPose& odometry,
                        const std::shared_ptr<const PreparedMap>& map, PoseFixData& fix);
  // A pose found at a frame (by a search, or by tracking a tracking start's
  // first frame) and the robot's odometry there.
  struct SearchResult {
    int64_t stamp_ns = 0;
    PoseWithCovariance T_world_camera_found;
    OdometryPose odometry;
  };
  enum class Proof { kAgrees, kUndecided, kContradicts };
  struct ProofVerdict {
    Proof proof;
    std::string outcome;
    // An undecided proof's farthest rival of the tracked pose (see below).
    PoseOffset rival = {};
  };
  // What the poses a proof search `found` around `tracked` say of tracking:
  // an OK pose elsewhere contradicts it only when the tracked pose scores
  // below ambiguous_score_fraction of it (verificationScore,
  // pose_acquisition.h). A pose elsewhere, OK or either of an ambiguous
  // search's two, that scores at least that fraction of the tracked pose is
  // its rival: the view does not tell them apart.
  ProofVerdict judgeProof(const LineSetData& line_set, const PreparedMap& map,
                          const Eigen::Isometry3d& tracked, const Localization& found) const;
  // Runs on the search worker: searches around `tracked`, the frame's
  // tracked pose, `moved_m` from the viewpoint of the tracking start at
  // `origin`, and proves or ends that tracking. A verdict on a start the
  // robot no longer tracks from is logged and dropped (see above).
  void prove(const LineSetData& line_set, const PreparedMap& map, const Eigen::Isometry3d& tracked,
             const SearchResult& origin, double moved_m);
  // Logs a search's outcome.
  static void logSearch(const char* kind, const LineSetData& line_set, const Alignment& alignment,
                        const SearchSummary& summary, const std::string& outcome,
                        int64_t search_ns);
  // Whether a pose found where `expected` was predicted lies within
  // confirm_position_m and confirm_rotation_rad of it.
  bool agrees(const Eigen::Isometry3d& expected, const Eigen::Isometry3d& found) const;
  // The robot's prediction, widened to proof_position_sigma_m at least, when a
  // proof search ended its tracking; else `prior`.
  PoseWithCovariance searchPrior(const std::string& robot_id, const PoseWithCovariance& prior);
  // Queues `run` on the search worker unless the robot's last search still
  // runs; an exception it throws is logged as `kind`'s failure.
  void submitSearch(const char* kind, const LineSetData& line_set, std::function<void()> run);
  void countSearch();
  // Stamps the total time and counts the answer; logs a slow one.
  PoseFixData finish(PoseFixData fix, int64_t start_ns);
  // Announces the robots' next tracked frames to the gate (frame_cadence.h).
  void announceNextFrame(const PoseFixData& fix, int64_t arrival_ns);

  struct StampedPosition {
    int64_t stamp_ns;
    Eigen::Vector3d position;
  };

  MapTileCache& map_;
  MessageLimits limits_;
  PipelineOptions options_;
  const int64_t silence_ns_;  // forget_robot_after_s
  // The proof search's prior sigmas (proof_position_sigma_m,
  // confirm_rotation_rad): the unproven part before one has looked around.
  const PoseOffset proof_reach_;
  mutable std::mutex counters_mutex_;
  BackboneCounters counters_;
  // The arrival of each robot's last LineSet, and when silent robots are next
  // looked for (see above).
  std::map<std::string, int64_t> last_heard_ns_;
  int64_t next_forgetting_ns_ = 0;
  std::map<std::string, StampedPosition> last_position_;
  std::map<std::string, PredictedMotion> motion_;
  std::map<std::string, FixScatter> fix_scatter_;
  // A found at odometry O_A moved by the robot's motion to odometry O: A O_A^-1 O;
  // nullopt when the two are of different epochs.
  static std::optional<PoseWithCovariance> movedByOdometry(const SearchResult& search,
                                                           const OdometryPose& odometry);
  // Where a robot's tracking started: a confirmed search result, or its
  // first frame tracked from its own prediction; and the proof searches that
  // agreed with tracking since (proven at agreeing_proofs_needed).
  struct TrackingStart {
    SearchResult origin;
    // Found by a search, and so carried (carriedSearch).
    bool searched = false;
    int agreeing_proofs = 0;
    // Motion from the origin's viewpoint (m) at which a proof search is due.
    double proof_due_m = 0.0;
    // The farthest rival undecided proofs found, which the unproven part of
    // the fixes covers until tracking is proven.
    PoseOffset rival = {};
    // Whether a proof search has aligned around tracking (OK or ambiguous):
    // until one has, no basin within its reach is ruled out.
    bool looked_around = false;
    // Whether this start is the one that began at `other`'s frame.
    bool startedAt(const SearchResult& other) const {
      return origin.stamp_ns == other.stamp_ns && origin.odometry.epoch == other.odometry.epoch;
    }
  };
  std::mutex searches_mutex_;
  // Each robot's acquisition; its frames are searched on the worker, one at a time.
  std::map<std::string, std::shared_ptr<AcquisitionSession>> acquisition_;
  std::map<std::string, TrackingStart> tracking_start_;
  // Robots whose tracking a proof search ended.
  std::set<std::string> searching_again_;
  // A robot's notices waiting for their LineSets, oldest first, and its last
  // LineSet taken for answering.
  struct RobotNotices {
    std::deque<Notice> waiting;
    FrameId last_line_set;
  };
  static constexpr size_t kMaxWaitingNotices = 4;
  std::mutex notices_mutex_;
  std::map<std::string, RobotNotices> notices_;
  // Open while a LineSet is handled; the workers below are its background.
  ForegroundGate foreground_;
  FrameCadence cadence_;
  PreparedMaps maps_;
  // Last, so that it is destroyed first: its searches use the members above.
  SearchWorker search_worker_;
};

lineloc_msg_FixStatus toFixStatus(AlignmentStatus status);

}  // namespace lineloc
