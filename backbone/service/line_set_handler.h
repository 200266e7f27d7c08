// Turns one received LineSet into its PoseFix (paper §3.2): validate it, take
// the model lines and faces near the predicted pose from the tile cache, and
// localize the camera in them (backbone/matching/localizer.h: hidden-line
// removal and alignment from a good prediction, a search from a poor one),
// and answer with the aligned pose and its covariance — or with a status that
// says why no pose can be trusted. Malformed input is dropped and counted; a
// map failure is answered with FIX_INTERNAL_ERROR and counted; serving goes on.
//
// A robot that states its camera height above the ground has its predicted
// height replaced by the model's ground level there plus that height (sigma
// ground_level_sigma_m) whenever its own is poorer: DGPS altitude is metres
// off, the street is not.
//
// What localization needs of a map view — the model segments, the ray-casting
// scene of the faces, the ground level — is built once per view, off the
// frames' path (prepared_maps.h); a frame with no map prepared near it yet
// is answered with FIX_NO_MATCH_COMPUTED.
//
// A frame whose prediction is too poor to track starts a search for the
// camera on a SearchWorker thread (search_worker.h), unless the robot's last
// search is still running, and is answered at once with
// FIX_NO_MATCH_COMPUTED: every LineSet is answered within the time of a
// tracked frame, never after a search. A pose found by a search is only taken
// once a second search, on a later frame of the same robot, finds the pose
// the first one predicts: the first found pose A1 moved by the robot's own
// motion between the two frames, A1 O1^-1 O2 (dead reckoning over a second is
// centimetres, DGPS metres), within confirm_position_m and
// confirm_rotation_rad of A2. A wrong pose the search picked by chance does
// not repeat. An ambiguous search between the two that ranks A1's pose second
// to another (its rival agrees with A1 moved, its best does not) votes
// against it: A1 then awaits no confirmation (seed 39 below: the search
// between its two confirming ones had the truth as its best, 1 cm off, and
// their pose as its rival; in the logs of nine runs of simulated Delft drives,
// such a search fell between the two of 9 of 290 confirmations, each that
// one; in 62 runs of seeds 1-50 since, it voted nine times, each against
// a pose 0.4-11.4 m off, seed 39's 1.6 m three times).
// Once confirmed, the robot's next frames are tracked from the
// confirmed pose moved the same way, A2 O2^-1 O, for carry_search_s. O is
// the robot's odometry pose, read from its predictions with the jumps of its
// DGPS corrections left out (predicted_motion.h): right after a start those
// move the prediction of a robot standing still by decimetres, and over 16
// simulated Delft drives all 6 searches that disagreed with the one before
// were both within 0.2 m of the truth.
//
// A confirmed search is no proof against a neighbouring basin: a robot that
// stands still searches the same view twice, and both searches can settle
// the same window's width off (simulated Delft seed 48: 0.31 m and 0.13 m,
// confirmed). Tracking from the carried pose therefore probes
// carried_start_step_m either way along the horizontal axes, not the
// tracking floor; and every OK fix keeps the acquired pose's resolution term
// (acquired_*_sigma, pose_acquisition.h) added to its covariance, and states
// it as the fix's unproven part (PoseFix::unproven_*: an offset the fixes
// share, which the robot fuses as one, inertial_navigator.h), until
// searches from other viewpoints agree with tracking: proof searches run on
// the worker over proof_position_sigma_m around the frame's tracked pose,
// the first at once, from the tracking start's own view, the others once
// the robot has moved acquisition_proven_after_m from where its confirmed
// search saw it. Tracking's covariance comes from the residuals of one
// view, which cannot tell the two basins apart; a view that changes can, but
// tracking from the wrong basin follows it there (seed 9: 0.5 m off for
// three metres of driving). Proof searches that agree, agreeing_proofs_needed
// of them from viewpoints at least proof_retry_m apart, end the widening: one
// can agree with tracking in the wrong basin itself (seed 9 again, with the
// frames' timing changed: a proof 0.6 m off agreed, and unwidened, 107 fixes
// lay beyond three sigma), and a basin that a changing view keeps is rarer.
// The first proves nothing by agreeing, as it sees the view the confirmed
// searches saw; it is there to find a basin their wider grid missed before
// tracking has followed it for a metre (seed 39 below). Until a proof search
// has aligned around tracking, the fixes' unproven part is that search's
// prior (proof_position_sigma_m, confirm_rotation_rad), as no basin within
// its reach is ruled out yet.
//
// One that finds the camera elsewhere ends the tracking only when the tracked
// pose, scored as the search scores its hypotheses (verificationScore,
// pose_acquisition.h), falls below ambiguous_score_fraction of the found one:
// the robot's frames are then searched for again, over at least
// proof_position_sigma_m, until two searches confirm each other on a pose
// narrow enough to track from: the robot's own prediction, however narrow,
// stands on the fixes the proof disproved. A search may miss the tracked pose's
// basin among its hypotheses; over 50 simulated Delft drives, both proof
// searches that ended tracking within 9 cm of the truth had found a pose 0.75 m
// and 0.9 m off that the truth outscored (17.1 to 14.1, 8.1 to 8.0). A pose
// elsewhere that scores within that fraction of the tracked one, found OK or as
// either pose of an ambiguous search, is a rival the view cannot tell from
// tracking: until tracking is proven, the unproven part of the fixes grows to
// the farthest such rival's distance and rotation from the tracked pose, so
// that a wrong basin is no precise answer. Simulated Delft seed 39 had two
// searches 13.07 and 13.27 s into its drive confirm a pose 1.75 m along its
// street (scoring 17.2 against a rival of 9.4; the truth was not among their
// hypotheses), and tracking followed it for 6 s: four proof searches were
// ambiguous, each with the truth as its best and the tracked pose as its rival
// (17.3 to 14.4 and alike), and 138 fixes lay beyond three sigma of covariances
// 0.15 m wide. With the rivals widening the fixes, 4 still did: two tracked
// before the first proof search had returned, and two tracked from the robot's
// own prediction, still on the disproven fixes, after two searches had
// confirmed the truth too wide to track from; none since. With the vote
// above, the search between those two leaves the pose unconfirmed: in two of
// three runs it voted, and nothing was tracked in their 20 s; the third's
// searches never found that pose and confirmed the truth at 15.7 s.
// One that finds nothing, or only poses near the tracked one, is tried again
// after proof_retry_m more. A proof judges the tracking start it was submitted
// for: a verdict that returns after the robot has started another (restarted
// or forgotten meanwhile; its searches wait for the proof) is dropped.
//
// A robot tracked from its own prediction, without a search of this backbone
// (one restarted mid-drive, a robot forgotten and back, a robot started from
// a known pose), is proven alike from its first tracked frame: its prediction
// stands on fixes whose proof this backbone never saw, or on none, and
// tracking keeps whichever basin it starts in. Its fixes state the same
// unproven part until proof searches from its tracking start agree. So is a
// robot whose odometry starts a new chain (predicted_motion.h: the robot
// restarted, or its frames came out of order): its motion since its tracking
// start is unknown.
//
// A tracked answer's covariance is raised to the sample covariance of the
// robot's answers of the last second and it, each moved to its frame by the
// robot's motion (fix_scatter.h): a view whose lines fit two alignments flips
// between them from frame to frame, each reporting its own basin's covariance.
//
// Each robot's predicted positions give its velocity; the tiles around where
// it will be `prefetch_lookahead_s` later are queued for loading, so steady
// frames find their map in memory.
//
// A robot may send each frame's LineSet without its features at the frame's
// exposure (ExposureTopic, common/messages/topics.h): the prediction the
// LineSet will carry. When that prediction is one to track in a map already
// prepared (a notice neither starts a preparation nor takes its error, which
// are the frame's), the hidden-line removal from it (visibleFromPrior,
// localizer.h) runs at once, on
// exposure_visibility_threads, while the robot extracts its lines, and the
// LineSet that follows takes it when its prior, map view and camera are the
// ones it was computed for, waiting for the rest of it if it is still running.
// It is then off the frame's exposure -> fix path: on the seven of simulated
// Delft seeds 1-8 that track (robot and backbone sharing two cores), the
// backbone's median answer went from 3.1-4.4 ms to 1.6-3.2 ms and exposure ->
// fix median from 6.0-7.3 ms to 5.0-6.6 ms; p99 did not move beyond the
// machine's noise, as the removal then competes with the robot's line
// extraction for the cores. A notice that comes after its LineSet, or after
// a later one (the notices' thread held up on a loaded machine), is skipped
// and counted: its frame has been answered, and the removal would only take
// a core from the next one. Notices wait for their LineSets in order, up to
// kMaxWaitingNotices per robot: a LineSets' thread a frame behind still
// finds its frame's notice, and leaves the next frame's for it.
//
// A robot not heard from for forget_robot_after_s is forgotten: its motion,
// recent answers, searches, proofs, notice and frame cadence are dropped, so
// that a backbone serving robots that come and go holds only the ones it
// serves (a forgotten notice held a prepared map of its own). One that comes
// back after that long is served as after a backbone restart: tracked from
// its own prediction and proven, or searched for when that is poor. The sweep runs on
// the LineSets' thread, at most every forget_robot_after_s / 2, at each
// LineSet and, while none comes, each time the serving loop wakes without
// one (forgetSilentRobotsWhenDue): a robot is forgotten between one and one
// and a half of that after its last LineSet, also when no robot is left.
//
// The searches and the map preparation are background work: they pause
// between pieces while a LineSet is being handled and from
// quiet_before_frame_ms before a tracked robot's next one is due
// (foreground_gate.h, frame_cadence.h).
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
  double confirm_position_m = 0.3;
  double confirm_rotation_rad = 0.5 * M_PI / 180.0;
  // An unconfirmed search result older than this is forgotten.
  double confirm_within_s = 5.0;
  // A confirmed search result starts tracking for this long after its frame.
  double carry_search_s = 1.0;
  // Tracking from a carried search probes this far along the horizontal axes
  // (LocalizerOptions::min_start_step_m). It starts only from a carried pose
  // within the tracking limits a robot's prediction must meet, although the
  // probes would reach a sigma of carried_start_step_m / start_sigma (0.33 m):
  // taking such wider poses too gave earlier first fixes on 29 simulated Delft
  // drives (seed 13 at 3.4 s instead of 11.9), but seed 20 then tracked two
  // searches that confirmed each other 9 m along its façade with 13 inliers,
  // 28 fixes beyond three sigma. A wide acquired covariance marks a poor match.
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
  // Runs on the search worker; `odometry` is the frame's.
  void search(const LineSetData& line_set, const OdometryPose& odometry, const PreparedMap& map,
              const PoseWithCovariance& prior);
  PoseWithCovariance groundedPrior(const LineSetData& line_set, const PreparedMap& map) const;
  // The prior a frame of `line_set`'s robot is tracked from in `map` unless a
  // confirmed search is carried: the prediction grounded and, for a robot
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
  enum class Confirmation { kConfirmed, kConfirmedTooWide, kFirst, kDisagrees };
  // A found pose's confirmation, for the search's log line.
  std::string describe(Confirmation confirmation, const PoseWithCovariance& found) const;
  // Whether `acquired` at `line_set`'s time confirms the robot's previous
  // search result (kFirst: there is none recent); remembers it for the next
  // one either way, and a confirmed one for carriedSearch. A confirmed one
  // too wide to track from (needsAcquisition) starts no tracking and leaves
  // a robot whose tracking a proof search ended searched for: its own
  // prediction stands on the fixes that proof disproved.
  Confirmation confirmPreviousSearch(const LineSetData& line_set, const OdometryPose& odometry,
                                     const PoseWithCovariance& acquired);
  // Whether the ambiguous search `found`, at `line_set`'s time, ranks the
  // robot's previous search result second to another pose (see above); if
  // so, forgets it, so that no search confirms it.
  bool outranksPreviousSearch(const LineSetData& line_set, const OdometryPose& odometry,
                              const Localization& found);
  // The robot's confirmed search result moved to `line_set`'s time, when
  // there is one to carry (see above).
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
  // How far one camera pose lies from another: the distance between the two
  // and the angle of the rotation between them.
  struct PoseOffset {
    double position_m = 0.0;
    double rotation_rad = 0.0;
    static PoseOffset between(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to);
    // Each of the two at the larger of its own and `other`'s.
    PoseOffset farthest(const PoseOffset& other) const;
  };
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
  static void logSearch(const char* kind, const LineSetData& line_set,
                        const Localization& localization, const std::string& outcome,
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
  std::map<std::string, SearchResult> last_search_;
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
