// Turns one received LineSet into its PoseFix (paper §3.2): validate it, take
// the model lines and faces near the predicted pose from the prepared map,
// localize the camera in them (localizer.h) and answer with the aligned pose
// and its covariance, or with a status that says why no pose can be trusted.
// Malformed input is dropped and counted; a map failure is answered with
// FIX_INTERNAL_ERROR and counted; serving goes on.
//
// Each robot's frames are answered by its session (robot_session.h): how a
// frame is localized (tracked from its prediction or from a taken hypothesis,
// or searched), the floor and the unproven part of an OK answer, and the
// proof searches of its tracking (tracking_proof.h). The handler validates,
// finds the map and the robot's session, runs the session's searches and
// proofs on the SearchWorker thread (search_worker.h) and answers.
//
// Maps. What localization needs of a map view is built once per view, off
// the frames' path (prepared_maps.h); a frame with no map prepared near it
// yet is answered with FIX_NO_MATCH_COMPUTED. The tiles around where a robot
// will be prefetch_lookahead_s later are queued for loading.
//
// Searches. A frame the session searches is answered at once with
// FIX_NO_MATCH_COMPUTED: no LineSet waits for a search. Its search runs on the
// worker unless the robot's last one still runs; a proof search likewise.
// When max_queued_searches wait already, the frame is answered FIX_BUSY
// instead (and a proof search is asked for again at the robot's next frame),
// and counted: a robot's search waits behind a bounded number of other
// robots' however many there are. Stopping drops the queued searches
// (search_worker.h), and destroying the handler cancels the one running.
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
// Robots. At most max_robots are served at once (robot_roster.h): the
// frames of a robot beyond them, heard from while that many are served, are
// answered FIX_BUSY at once, counted, and given no session. A robot not heard
// from (by LineSet or exposure notice) for forget_robot_after_s is forgotten
// (its session, notices and cadence), so that a backbone serving robots that
// come and go holds only the ones it serves; one that comes back is served as
// after a backbone restart. The sweep runs on the LineSets' thread, at most
// every forget_robot_after_s / 2.
//
// Backbones. Where several share the robots (backbone_peers.h), a robot left
// to another backbone is forgotten here at once, so that one taken back is
// served as a robot new here. Each frame answered hands the robot's tracking
// proof over (HandoverChannel::publish, tracking_proof.h), and a robot new
// here is offered the newest handover of it (HandoverChannel::latest) at each
// frame until its tracking is proven here: a robot taken over continues the
// proof of the backbone before.
//
// Logs. What outside input causes at any rate (drops, refusals) and what
// each frame may meet (a map that fails while the database is down) is
// logged at most kLoggedPerSecond times a second each, the rest summarised
// (rate_limited_log.h); the counters count every one.
//
// Threads. LineSets of different robots may be answered at once, on
// threads of their own (frame_workers.h), each robot's one at a time; a
// frame answered beside k - 1 others localizes on hardwareThreads() / k of
// them (LocalizerOptions::threads 0; at least one), so that the frames in
// hand share the cores.
//
// Background work. Searches, map preparation and learning pause between
// pieces while a LineSet is being handled and from quiet_before_frame_ms
// before a tracked robot's next one is due (foreground_gate.h,
// frame_cadence.h).
//
// Learning. With PipelineOptions::learning.db set, each tracked frame
// answered OK is offered to the learning of lines (online_learning.h), and a
// robot forgotten here has what it learnt written.
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "backbone/map/map_tile_cache.h"
#include "backbone/matching/localizer.h"
#include "backbone/service/fair_frame_queue.h"
#include "backbone/service/frame_cadence.h"
#include "backbone/service/online_learning.h"
#include "backbone/service/prepared_maps.h"
#include "backbone/service/robot_roster.h"
#include "backbone/service/robot_session.h"
#include "backbone/service/search_worker.h"
#include "common/geodesy/site_sun.h"
#include "common/logging/rate_limited_log.h"
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
  // Frames answered FIX_BUSY as max_robots others were served.
  uint64_t refused_robot_frames = 0;
  // Searches and proof searches not queued as max_queued_searches waited
  // (each search's frame answered FIX_BUSY).
  uint64_t refused_searches = 0;
  // Frames answered FIX_BUSY as a newer one of their robot came before they
  // were handled, or as they would have been answered after it.
  uint64_t superseded_frames = 0;
  uint64_t late_frames = 0;
  // The backbones alive on the domain, this one among them, and the frames
  // left to the others, whose robots they serve (backbone_peers.h).
  uint64_t backbones = 1;
  uint64_t frames_served_elsewhere = 0;
  // Learning lines from the frames answered (online_learning.h).
  LearningCounters learning;
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
  // Robots served at once, and searches waiting in all (see above).
  int max_robots = 64;
  int max_queued_searches = 8;
  RobotSessionOptions robot;
  LocalizerOptions localizer;
  // When set, each LineSet is localized under the sun of its stamp instead
  // of localizer.visibility.sunlight (none while the sun is down).
  std::optional<SiteSun> sun_from_clock;
  // Learning from the frames answered, when learning.db is set.
  OnlineLearningOptions learning;
};

// How a backbone's sessions hand their robots' tracking over to the backbone
// that takes them over (tracking_handovers.h); empty for a backbone alone.
// Both are called from the handler's threads.
struct HandoverChannel {
  std::function<void(const std::string& robot_id, const TrackingHandover& handover)> publish;
  std::function<std::optional<TrackingHandover>(const std::string& robot_id)> latest;
};

// The sun a LineSet taken at `stamp_ns` is localized under: the clock's when
// options.sun_from_clock is set (none while it is down), else the localizer's.
std::optional<Sunlight> sunlightAt(const PipelineOptions& options, int64_t stamp_ns);

class LineSetHandler {
 public:
  LineSetHandler(MapTileCache& map, const MessageLimits& limits, const PipelineOptions& options,
                 HandoverChannel handovers = {});
  // Cancels the searches and map preparation under way (foreground_gate.h)
  // and drops the queued ones, so that it ends promptly.
  ~LineSetHandler();
  LineSetHandler(const LineSetHandler&) = delete;
  LineSetHandler& operator=(const LineSetHandler&) = delete;

  // The fix to publish, or nullopt when the message was dropped: accept()
  // then answer().
  std::optional<PoseFixData> handle(const lineloc_msg_LineSet& message);

  // Counts `message` received and checks it: its data, or nullopt when it
  // was dropped (malformed, beyond the limits).
  std::optional<LineSetData> accept(const lineloc_msg_LineSet& message);
  // The fix for an accepted LineSet taken at `taken_ns` (steady clock);
  // its total time counts from then.
  PoseFixData answer(const LineSetData& line_set, int64_t taken_ns);
  // FIX_BUSY, counted, for an accepted LineSet not localized: a newer one
  // of its robot superseded it, or it would have been answered after that
  // one (fair_frame_queue.h).
  PoseFixData answerBusy(const LineSetData& line_set, int64_t taken_ns, FrameRefusal why);

  // A frame's exposure notice (see above); a malformed one is dropped and
  // counted. Safe to call beside handle().
  void handleExposure(const lineloc_msg_LineSet& message);

  // Forgets the robots not heard from for forget_robot_after_s before
  // `now_ns` (steady clock); answer() calls the second itself (see above).
  void forgetSilentRobots(int64_t now_ns);
  // The same, unless a sweep ran within forget_robot_after_s / 2.
  void forgetSilentRobotsWhenDue(int64_t now_ns);

  // Blocks until the searches under way have finished.
  void waitForSearches();

  // Blocks until the frames offered to learning, and the robots' finished
  // pieces, have been learnt and written (if learning is on).
  void waitForLearning();

  // Ends learning, if on: the frames waiting are dropped and what every
  // robot learnt is written (online_learning.h).
  void stopLearning();

  // From now on each LineSet is localized under the sun of its stamp over
  // the site (PipelineOptions::sun_from_clock): for a site looked up once
  // serving has started. Safe to call beside handle().
  void takeSunFromClock(const SiteSun& sun);

  // Logs the summaries of the drops and refusals not logged (see above),
  // once their interval has ended; call now and then.
  void flushLogs(int64_t now_ns);

  BackboneCounters counters() const;

  // Records how many backbones are alive.
  void countBackbones(size_t alive);
  // Counts a frame of `robot_id` left to the backbone that serves it, and
  // forgets the robot here (see above).
  void leaveToAnotherBackbone(const std::string& robot_id);

  // Counts a dropped message (malformed, or refused before handle()) and
  // logs `kind`'s drop with `error`.
  void countDrop(const char* kind, uint32_t sequence_number, const std::string& error);

 private:
  // Records that `robot_id`'s LineSet arrived at `arrival_ns` (steady
  // clock), first forgetting the silent robots when that is due: itself too
  // when it was one. False when the robot is refused (see above).
  bool hearFrom(const std::string& robot_id, int64_t arrival_ns);
  // Records the roster's answer for a robot heard from; false when refused.
  bool served(RobotRoster::Heard heard);
  // Drops the sessions, notices and cadence of the robots the roster no
  // longer serves.
  void dropRobotsNotServed();
  // The robot's session, made when it has none.
  std::shared_ptr<RobotSession> sessionOf(const std::string& robot_id);
  void prefetchAlongMotion(RobotSession& session, const LineSetData& line_set);
  // The localizer's options for `line_set`: under sunlightAt its stamp.
  LocalizerOptions localizerOptions(const LineSetData& line_set) const;
  // Tracks `line_set` as `plan` says into `fix` and submits the proof search
  // its session asks for. `visible_from_prior`, when given, is the hidden-line
  // removal for it.
  void track(const std::shared_ptr<RobotSession>& session, const LineSetData& line_set,
             const OdometryPose& odometry, const std::shared_ptr<const PreparedMap>& map,
             const RobotSession::FramePlan& plan, PoseFixData& fix,
             const std::vector<VisibleSegment>* visible_from_prior = nullptr);
  // Run on the search worker: the session searches the frame, or proves its
  // tracking at it, and the outcome is logged.
  void search(RobotSession& session, const LineSetData& line_set, const OdometryPose& odometry,
              std::shared_ptr<const PreparedMap> map, const PoseWithCovariance& prior);
  void prove(RobotSession& session, const LineSetData& line_set, const PreparedMap& map,
             const Eigen::Isometry3d& tracked, const ProofRequest& request);
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
  // Localizes a served robot's frame as its session plans into `fix`
  // (timed from `start_ns`): tracked, or searched on the worker.
  PoseFixData localizeFrame(const std::shared_ptr<RobotSession>& session,
                            const LineSetData& line_set, const OdometryPose& odometry,
                            std::optional<Notice> notice, PoseFixData fix, int64_t start_ns);
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
  // Logs a search's outcome.
  static void logSearch(const char* kind, const LineSetData& line_set, const Alignment& alignment,
                        const SearchSummary& summary, const std::string& outcome,
                        int64_t search_ns);
  // Queues `run` on the search worker unless the robot's last search still
  // runs or the queue is full (counted); an exception it throws is logged as
  // `kind`'s failure.
  SearchWorker::Submitted submitSearch(const char* kind, const LineSetData& line_set,
                                       std::function<void()> run);
  void countSearch();
  // Announces the robot's next frame and counts the answer (countAnswer).
  PoseFixData finish(PoseFixData fix, int64_t start_ns);
  // Stamps the total time and counts the answer; logs a slow one.
  PoseFixData countAnswer(PoseFixData fix, int64_t start_ns);
  // Announces the robots' next tracked frames to the gate (frame_cadence.h).
  void announceNextFrame(const PoseFixData& fix, int64_t arrival_ns);

  static constexpr int kLoggedPerSecond = 5;

  MapTileCache& map_;
  MessageLimits limits_;
  HandoverChannel handovers_;
  // Its sun_from_clock under sun_mutex_ (takeSunFromClock).
  PipelineOptions options_;
  mutable std::mutex sun_mutex_;
  const int64_t silence_ns_;  // forget_robot_after_s
  mutable std::mutex counters_mutex_;
  BackboneCounters counters_;
  RateLimitedLog drop_log_;
  RateLimitedLog busy_log_;
  RateLimitedLog map_failure_log_;
  // The robots served, and when silent ones are next looked for (see above).
  RobotRoster roster_;
  std::atomic<int64_t> next_forgetting_ns_{0};
  // Each robot's session; a search that outlives its robot's keeps its own.
  std::mutex sessions_mutex_;
  std::map<std::string, std::shared_ptr<RobotSession>> sessions_;
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
  // LineSets being answered now (see above: threads).
  std::atomic<int> frames_in_hand_{0};
  FrameCadence cadence_;
  PreparedMaps maps_;
  // Null without learning.
  std::unique_ptr<OnlineLearning> learning_;
  // Last, so that it is destroyed first: its searches use the members above.
  SearchWorker search_worker_;
};

}  // namespace lineloc
