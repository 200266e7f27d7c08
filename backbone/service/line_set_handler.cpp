#include "backbone/service/line_set_handler.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/parallel/parallel_for.h"
#include "common/time/clock.h"

namespace lineloc {
namespace {

// The answer to `line_set` before it is localized: its frame, its prediction.
PoseFixData answerTo(const LineSetData& line_set) {
  PoseFixData fix;
  fix.robot_id = line_set.robot_id;
  fix.sequence_number = line_set.sequence_number;
  fix.stamp_ns = line_set.stamp_ns;
  fix.T_world_camera = line_set.predicted_T_world_camera;
  return fix;
}

// Counts a frame in hand while it lives.
class FramesInHand {
 public:
  explicit FramesInHand(std::atomic<int>& count) : count_(count) { ++count_; }
  ~FramesInHand() { --count_; }
  FramesInHand(const FramesInHand&) = delete;
  FramesInHand& operator=(const FramesInHand&) = delete;

 private:
  std::atomic<int>& count_;
};

}  // namespace

LineSetHandler::LineSetHandler(MapTileCache& map, const MessageLimits& limits,
                               const PipelineOptions& options, HandoverChannel handovers)
    : map_(map),
      limits_(limits),
      handovers_(std::move(handovers)),
      options_(options),
      silence_ns_(static_cast<int64_t>(options.forget_robot_after_s * 1e9)),
      drop_log_("dropped messages", kLoggedPerSecond, 1.0),
      busy_log_("frames answered busy", kLoggedPerSecond, 1.0),
      map_failure_log_("map failures", kLoggedPerSecond, 1.0, spdlog::level::err),
      roster_(static_cast<size_t>(std::max(options.max_robots, 0)), silence_ns_),
      foreground_(fromMilliseconds(options.max_background_yield_ms)),
      cadence_(fromMilliseconds(options.quiet_before_frame_ms),
               fromMilliseconds(options.max_background_yield_ms)),
      maps_(map, options.query_radius_m, options.map_reuse_distance_m, &foreground_),
      learning_(options.learning.db.empty()
                    ? nullptr
                    : std::make_unique<OnlineLearning>(options.learning, &foreground_)),
      search_worker_(&foreground_, static_cast<size_t>(std::max(options.max_queued_searches, 0))) {}

LineSetHandler::~LineSetHandler() {
  foreground_.cancelBackground();
}

void LineSetHandler::waitForSearches() {
  maps_.waitUntilIdle();
  search_worker_.waitUntilIdle();
}

void LineSetHandler::waitForLearning() {
  if (learning_) {
    learning_->waitUntilIdle();
  }
}

void LineSetHandler::stopLearning() {
  if (learning_) {
    learning_->stop();
  }
}

void LineSetHandler::flushLogs(int64_t now_ns) {
  drop_log_.flush(now_ns);
  busy_log_.flush(now_ns);
  map_failure_log_.flush(now_ns);
}

BackboneCounters LineSetHandler::counters() const {
  BackboneCounters counters;
  {
    const std::lock_guard<std::mutex> lock(counters_mutex_);
    counters = counters_;
  }
  if (learning_) {
    counters.learning = learning_->counters();
  }
  return counters;
}

bool LineSetHandler::hearFrom(const std::string& robot_id, int64_t arrival_ns) {
  forgetSilentRobotsWhenDue(arrival_ns);
  return served(roster_.hear(robot_id, arrival_ns));
}

bool LineSetHandler::served(RobotRoster::Heard heard) {
  if (heard == RobotRoster::Heard::kServed) {
    return true;
  }
  const std::lock_guard<std::mutex> lock(counters_mutex_);
  counters_.robots = roster_.size();
  return heard == RobotRoster::Heard::kNew;
}

void LineSetHandler::forgetSilentRobotsWhenDue(int64_t now_ns) {
  int64_t due_ns = next_forgetting_ns_;
  if (now_ns < due_ns ||
      !next_forgetting_ns_.compare_exchange_strong(due_ns, now_ns + silence_ns_ / 2)) {
    return;
  }
  forgetSilentRobots(now_ns);
}

void LineSetHandler::forgetSilentRobots(int64_t now_ns) {
  const std::vector<RobotRoster::Forgotten> forgotten = roster_.forgetSilent(now_ns);
  for (const RobotRoster::Forgotten& robot : forgotten) {
    spdlog::info("forgetting robot {}: not heard from for {:.1f} s", robot.robot_id,
                 robot.silent_ns * 1e-9);
  }
  dropRobotsNotServed();
  const std::lock_guard<std::mutex> lock(counters_mutex_);
  counters_.robots_forgotten += forgotten.size();
}

void LineSetHandler::dropRobotsNotServed() {
  const auto unheard = [this](const std::string& robot_id) { return !roster_.serves(robot_id); };
  cadence_.forget(unheard);
  {
    const std::lock_guard<std::mutex> lock(sessions_mutex_);
    std::erase_if(sessions_, [&](const auto& robot) {
      if (!unheard(robot.first)) {
        return false;
      }
      if (learning_) {
        learning_->finishRobot(robot.first);
      }
      return true;
    });
  }
  {
    const std::lock_guard<std::mutex> lock(notices_mutex_);
    std::erase_if(notices_, [&](const auto& robot) { return unheard(robot.first); });
  }
  const std::lock_guard<std::mutex> lock(counters_mutex_);
  counters_.robots = roster_.size();
}

std::shared_ptr<RobotSession> LineSetHandler::sessionOf(const std::string& robot_id) {
  const std::lock_guard<std::mutex> lock(sessions_mutex_);
  std::shared_ptr<RobotSession>& session = sessions_[robot_id];
  if (!session) {
    session = std::make_shared<RobotSession>(options_.robot, options_.localizer);
  }
  return session;
}

void LineSetHandler::prefetchAlongMotion(RobotSession& session, const LineSetData& line_set) {
  if (const std::optional<Eigen::Vector3d> ahead =
          session.positionAhead(line_set, options_.prefetch_lookahead_s)) {
    map_.prefetch(*ahead, options_.query_radius_m);
  }
}

std::optional<Sunlight> sunlightAt(const PipelineOptions& options, int64_t stamp_ns) {
  if (options.sun_from_clock) {
    return options.sun_from_clock->at(stamp_ns);
  }
  return options.localizer.visibility.sunlight;
}

LocalizerOptions LineSetHandler::localizerOptions(const LineSetData& line_set) const {
  LocalizerOptions options = options_.localizer;
  if (options.threads <= 0) {
    options.threads = std::max(1, hardwareThreads() / std::max(frames_in_hand_.load(), 1));
  }
  const std::lock_guard<std::mutex> lock(sun_mutex_);
  options.visibility.sunlight = sunlightAt(options_, line_set.stamp_ns);
  return options;
}

void LineSetHandler::takeSunFromClock(const SiteSun& sun) {
  const std::lock_guard<std::mutex> lock(sun_mutex_);
  options_.sun_from_clock = sun;
}

void LineSetHandler::track(const std::shared_ptr<RobotSession>& session,
                           const LineSetData& line_set, const OdometryPose& odometry,
                           const std::shared_ptr<const PreparedMap>& map,
                           const RobotSession::FramePlan& plan, PoseFixData& fix,
                           const std::vector<VisibleSegment>* visible_from_prior) {
  LocalizerOptions options = localizerOptions(line_set);
  options.min_start_step_m = std::max(options.min_start_step_m, plan.min_start_step_m);
  const Localization localization =
      localize(line_set.segments, line_set.corners, map->segments, map->scene, plan.prior,
               line_set.camera, options, visible_from_prior);
  const RobotSession::Answered answered = session->answer(line_set, odometry, localization, fix);
  if (learning_ && fix.status == lineloc_msg_FIX_OK) {
    const std::optional<Sunlight>& sunlight = options.visibility.sunlight;
    learning_->offer(line_set, fix.T_world_camera, map, localization.visible,
                     sunlight ? std::optional(sunlight->direction_world) : std::nullopt);
  }
  if (answered.resumed) {
    spdlog::info("tracking {} from #{} on continues the proof its last backbone handed over",
                 line_set.robot_id, line_set.sequence_number);
  } else if (answered.started_from_prediction) {
    spdlog::info(
        "tracking {} from #{} on from its own prediction, which no search here found: its "
        "fixes stay widened until proof searches agree",
        line_set.robot_id, line_set.sequence_number);
  }
  if (answered.proof_due) {
    submitSearch(
        "proof search", line_set,
        [this, session, line_set, map, tracked = fix.T_world_camera.pose,
         request = *answered.proof_due] { prove(*session, line_set, *map, tracked, request); });
  }
}

namespace {

// Where a pose puts the camera, and its optical axis' azimuth clockwise from
// grid north: atan2(r_x, r_y) of R's third column.
std::string describePose(const Eigen::Isometry3d& T_world_camera) {
  const Eigen::Vector3d axis_world = T_world_camera.linear().col(2);
  return fmt::format("({:.2f}, {:.2f}, {:.2f}) m looking {:.2f} deg",
                     T_world_camera.translation().x(), T_world_camera.translation().y(),
                     T_world_camera.translation().z(),
                     std::atan2(axis_world.x(), axis_world.y()) * 180.0 / M_PI);
}

}  // namespace

void LineSetHandler::search(RobotSession& session, const LineSetData& line_set,
                            const OdometryPose& odometry, std::shared_ptr<const PreparedMap> map,
                            const PoseWithCovariance& prior) {
  const int64_t start_ns = steadyClockNs();
  const AcquisitionSession::Searched searched =
      session.search(line_set, odometry, std::move(map), prior, localizerOptions(line_set));
  const int64_t search_ns = steadyClockNs() - start_ns;
  countSearch();
  const Alignment& alignment = searched.acquisition.alignment;
  std::string outcome = alignment.message.empty() ? "" : alignment.message + "; ";
  outcome += fmt::format("{} hypotheses kept", searched.hypotheses);
  if (!searched.decision) {
    outcome += "; undecided: " + searched.undecided;
  } else {
    outcome += fmt::format(
        "; takes one at {} with posterior {:.4f}, covering rivals up to {:.2f} m and {:.2f} deg: "
        "tracking",
        describePose(searched.decision->hypothesis.T_world_camera.pose),
        searched.decision->posterior, searched.decision->covered.position_m,
        searched.decision->covered.rotation_rad * 180.0 / M_PI);
  }
  logSearch("search", line_set, alignment, searched.acquisition.summary, outcome, search_ns);
}

void LineSetHandler::prove(RobotSession& session, const LineSetData& line_set,
                           const PreparedMap& map, const Eigen::Isometry3d& tracked,
                           const ProofRequest& request) {
  const int64_t start_ns = steadyClockNs();
  const RobotSession::Proved proved =
      session.prove(line_set, map, tracked, request, localizerOptions(line_set));
  const int64_t search_ns = steadyClockNs() - start_ns;
  countSearch();
  std::string outcome = proved.verdict.outcome;
  if (!proved.applied) {
    outcome += "; dropped, as the robot no longer tracks from the start it judged";
  }
  logSearch("proof search", line_set, proved.localization.alignment,
            proved.localization.search.value_or(SearchSummary{}), outcome, search_ns);
}

void LineSetHandler::logSearch(const char* kind, const LineSetData& line_set,
                               const Alignment& alignment, const SearchSummary& summary,
                               const std::string& outcome, int64_t search_ns) {
  const std::string rival = summary.T_world_camera_rival
                                ? ", rival at " + describePose(*summary.T_world_camera_rival)
                                : "";
  const auto carried_aligned = std::ranges::count_if(
      summary.aligned_hypotheses,
      [](const ScoredHypothesis& aligned) { return aligned.carried_index >= 0; });
  spdlog::info(
      "{} for {} #{}: {} ({}); {} of {} grid hypotheses and {} carried ones aligned, "
      "verification scores {:.1f} best / {:.1f} rival, {} inliers, best at {}{}, {:.0f} ms (grid "
      "search {:.0f} ms)",
      kind, line_set.robot_id, line_set.sequence_number, toString(toFixStatus(alignment.status)),
      outcome, summary.aligned - carried_aligned, summary.hypotheses, carried_aligned,
      summary.best_score, summary.rival_score, alignment.inliers,
      describePose(alignment.T_world_camera.pose), rival, toMilliseconds(search_ns),
      toMilliseconds(summary.search_ns));
}

SearchWorker::Submitted LineSetHandler::submitSearch(const char* kind, const LineSetData& line_set,
                                                     std::function<void()> run) {
  const SearchWorker::Submitted submitted = search_worker_.submit(
      line_set.robot_id, [kind, robot_id = line_set.robot_id, sequence = line_set.sequence_number,
                          run = std::move(run)] {
        try {
          run();
        } catch (const BackgroundWorkCancelled&) {
          // The handler is being destroyed.
        } catch (const std::exception& error) {
          spdlog::error("{} for {} #{} failed: {}", kind, robot_id, sequence, error.what());
        }
      });
  if (submitted == SearchWorker::Submitted::kQueueFull) {
    busy_log_.log(fmt::format("{} for {} #{} not queued: {} searches wait already", kind,
                              line_set.robot_id, line_set.sequence_number,
                              options_.max_queued_searches));
    const std::lock_guard<std::mutex> lock(counters_mutex_);
    ++counters_.refused_searches;
  }
  return submitted;
}

void LineSetHandler::countBackbones(size_t alive) {
  const std::lock_guard<std::mutex> lock(counters_mutex_);
  counters_.backbones = alive;
}

void LineSetHandler::leaveToAnotherBackbone(const std::string& robot_id) {
  if (roster_.forget(robot_id)) {
    spdlog::info("robot {} is served by another backbone from now on", robot_id);
    dropRobotsNotServed();
  }
  const std::lock_guard<std::mutex> lock(counters_mutex_);
  ++counters_.frames_served_elsewhere;
}

void LineSetHandler::countSearch() {
  const std::lock_guard<std::mutex> lock(counters_mutex_);
  ++counters_.searches;
}

void LineSetHandler::announceNextFrame(const PoseFixData& fix, int64_t arrival_ns) {
  const bool tracked = fix.status != lineloc_msg_FIX_NO_MATCH_COMPUTED &&
                       fix.status != lineloc_msg_FIX_NO_MAP_LINES &&
                       fix.status != lineloc_msg_FIX_INTERNAL_ERROR &&
                       fix.status != lineloc_msg_FIX_BUSY;
  cadence_.add(fix.robot_id, fix.stamp_ns, arrival_ns, tracked);
  foreground_.expectForegroundFrom(cadence_.quietFrom_ns(steadyClockNs()));
}

PoseFixData LineSetHandler::finish(PoseFixData fix, int64_t start_ns) {
  announceNextFrame(fix, start_ns);
  return countAnswer(std::move(fix), start_ns);
}

PoseFixData LineSetHandler::countAnswer(PoseFixData fix, int64_t start_ns) {
  fix.timings.total = steadyClockNs() - start_ns;
  const StageTimingsNs& timings = fix.timings;
  if (timings.total > fromMilliseconds(options_.slow_answer_ms)) {
    spdlog::warn(
        "LineSet for {} #{} answered in {:.1f} ms: map {:.1f}, visibility {:.1f}, matching "
        "{:.1f}, pose {:.1f} ms",
        fix.robot_id, fix.sequence_number, toMilliseconds(timings.total),
        toMilliseconds(timings.map), toMilliseconds(timings.visibility),
        toMilliseconds(timings.matching), toMilliseconds(timings.pose));
  }
  const std::lock_guard<std::mutex> lock(counters_mutex_);
  ++counters_.answered;
  counters_.fixes_ok += fix.status == lineloc_msg_FIX_OK ? 1 : 0;
  std::vector<StageTimingsNs>& recent = counters_.recent_timings;
  if (recent.size() < kTimingWindow) {
    recent.push_back(fix.timings);
  } else {
    recent[counters_.answered % kTimingWindow] = fix.timings;
  }
  return fix;
}

std::optional<PoseFixData> LineSetHandler::handle(const lineloc_msg_LineSet& message) {
  const int64_t taken_ns = steadyClockNs();
  const std::optional<LineSetData> line_set = accept(message);
  if (!line_set) {
    return std::nullopt;
  }
  return answer(*line_set, taken_ns);
}

std::optional<LineSetData> LineSetHandler::accept(const lineloc_msg_LineSet& message) {
  {
    const std::lock_guard<std::mutex> lock(counters_mutex_);
    ++counters_.received;
  }
  if (const std::optional<std::string> error = findLineSetError(message, limits_)) {
    countDrop("LineSet", message.sequence_number, *error);
    return std::nullopt;
  }
  return fromMessage(message);
}

PoseFixData LineSetHandler::answerBusy(const LineSetData& line_set, int64_t taken_ns,
                                       FrameRefusal why) {
  const bool superseded = why == FrameRefusal::kSuperseded;
  busy_log_.log(taken_ns, fmt::format("LineSet of {} #{} answered busy: {}", line_set.robot_id,
                                      line_set.sequence_number,
                                      superseded ? "superseded by a newer one before it was handled"
                                                 : "it would be answered after the robot's next"));
  {
    const std::lock_guard<std::mutex> lock(counters_mutex_);
    ++(superseded ? counters_.superseded_frames : counters_.late_frames);
  }
  PoseFixData fix = answerTo(line_set);
  fix.status = lineloc_msg_FIX_BUSY;
  return countAnswer(fix, taken_ns);
}

PoseFixData LineSetHandler::answer(const LineSetData& line_set, int64_t taken_ns) {
  const ForegroundGate::Scope foreground(foreground_);
  const FramesInHand in_hand(frames_in_hand_);
  const int64_t start_ns = steadyClockNs();
  PoseFixData fix = answerTo(line_set);
  if (!hearFrom(line_set.robot_id, taken_ns)) {
    busy_log_.log(taken_ns,
                  fmt::format("LineSet of {} #{} answered busy: {} robots are served",
                              line_set.robot_id, line_set.sequence_number, options_.max_robots));
    {
      const std::lock_guard<std::mutex> lock(counters_mutex_);
      ++counters_.refused_robot_frames;
    }
    fix.status = lineloc_msg_FIX_BUSY;
    return countAnswer(fix, taken_ns);
  }
  std::optional<Notice> notice = takeNotice(line_set);
  const std::shared_ptr<RobotSession> session = sessionOf(line_set.robot_id);
  const OdometryPose odometry = session->hear(line_set);
  if (handovers_.latest && session->awaitsHandover()) {
    if (const std::optional<TrackingHandover> handover = handovers_.latest(line_set.robot_id)) {
      session->offerHandover(*handover);
    }
  }
  fix = localizeFrame(session, line_set, odometry, std::move(notice), std::move(fix), start_ns);
  if (handovers_.publish) {
    handovers_.publish(line_set.robot_id, session->handover(line_set.stamp_ns, odometry));
  }
  return finish(fix, taken_ns);
}

PoseFixData LineSetHandler::localizeFrame(const std::shared_ptr<RobotSession>& session,
                                          const LineSetData& line_set, const OdometryPose& odometry,
                                          std::optional<Notice> notice, PoseFixData fix,
                                          int64_t start_ns) {
  try {
    const std::shared_ptr<const PreparedMap> map =
        maps_.around(line_set.predicted_T_world_camera.pose.translation());
    fix.timings.map = steadyClockNs() - start_ns;
    prefetchAlongMotion(*session, line_set);
    if (!map) {
      fix.status = lineloc_msg_FIX_NO_MATCH_COMPUTED;
      return fix;
    }
    fix.model_lines = static_cast<uint32_t>(map->view->lines.size());
    if (map->view->lines.empty()) {
      fix.status = lineloc_msg_FIX_NO_MAP_LINES;
      return fix;
    }
    const RobotSession::FramePlan plan = session->planFor(line_set, odometry, *map);
    if (plan.plan == RobotSession::Plan::kTrack) {
      const int64_t waiting_start_ns = steadyClockNs();
      const std::optional<std::vector<VisibleSegment>> ahead =
          visibilityAhead(line_set, std::move(notice), map, plan.prior);
      fix.timings.visibility = ahead ? steadyClockNs() - waiting_start_ns : 0;
      track(session, line_set, odometry, map, plan, fix, ahead ? &*ahead : nullptr);
      return fix;
    }
    const SearchWorker::Submitted submitted = submitSearch(
        "search", line_set, [this, session, line_set, odometry, map, prior = plan.prior] {
          search(*session, line_set, odometry, map, prior);
        });
    fix.status = submitted == SearchWorker::Submitted::kQueueFull
                     ? lineloc_msg_FIX_BUSY
                     : lineloc_msg_FIX_NO_MATCH_COMPUTED;
  } catch (const std::exception& error) {
    map_failure_log_.log(start_ns, fmt::format("map for {} #{} failed: {}", fix.robot_id,
                                               fix.sequence_number, error.what()));
    const std::lock_guard<std::mutex> lock(counters_mutex_);
    ++counters_.map_errors;
    fix.status = lineloc_msg_FIX_INTERNAL_ERROR;
  }
  return fix;
}

void LineSetHandler::countDrop(const char* kind, uint32_t sequence_number,
                               const std::string& error) {
  drop_log_.log(fmt::format("dropped {} #{}: {}", kind, sequence_number, error));
  const std::lock_guard<std::mutex> lock(counters_mutex_);
  ++counters_.dropped_invalid;
  counters_.last_drop_reason = error;
}

void LineSetHandler::handleExposure(const lineloc_msg_LineSet& message) {
  const ForegroundGate::Scope foreground(foreground_);
  if (const std::optional<std::string> error = findLineSetError(message, limits_)) {
    countDrop("exposure notice", message.sequence_number, *error);
    return;
  }
  if (!served(roster_.hear(message.robot_id, steadyClockNs()))) {
    return;
  }
  const LineSetData exposure = fromMessage(message);
  std::promise<std::vector<VisibleSegment>> visible;
  try {
    const std::shared_ptr<const PreparedMap> map =
        maps_.preparedAround(exposure.predicted_T_world_camera.pose.translation());
    if (!map || map->view->lines.empty()) {
      return;
    }
    const PoseWithCovariance prior = sessionOf(exposure.robot_id)->prior(exposure, *map);
    if (needsAcquisition(prior, options_.localizer)) {
      return;
    }
    Notice notice{{exposure.sequence_number, exposure.stamp_ns},
                  map,
                  prior,
                  exposure.camera,
                  visible.get_future().share()};
    if (!aheadOfLineSet(exposure.robot_id, std::move(notice))) {
      const std::lock_guard<std::mutex> lock(counters_mutex_);
      ++counters_.notices_after_line_set;
      return;
    }
    LocalizerOptions options = localizerOptions(exposure);
    options.threads = options_.exposure_visibility_threads;
    visible.set_value(visibleFromPrior(map->segments, map->scene, prior, exposure.camera, options));
  } catch (const std::exception& error) {
    spdlog::error("exposure notice for {} #{} failed: {}", exposure.robot_id,
                  exposure.sequence_number, error.what());
    visible.set_exception(std::current_exception());
  }
}

bool LineSetHandler::aheadOfLineSet(const std::string& robot_id, Notice notice) {
  const std::lock_guard<std::mutex> lock(notices_mutex_);
  RobotNotices& robot = notices_[robot_id];
  if (notice.frame.stamp_ns <= robot.last_line_set.stamp_ns) {
    return false;
  }
  if (robot.waiting.size() == kMaxWaitingNotices) {
    robot.waiting.pop_front();
  }
  robot.waiting.push_back(std::move(notice));
  return true;
}

std::optional<LineSetHandler::Notice> LineSetHandler::takeNotice(const LineSetData& line_set) {
  const FrameId frame{line_set.sequence_number, line_set.stamp_ns};
  const std::lock_guard<std::mutex> lock(notices_mutex_);
  RobotNotices& robot = notices_[line_set.robot_id];
  robot.last_line_set = frame;
  std::optional<Notice> taken;
  if (const auto found = std::ranges::find(robot.waiting, frame, &Notice::frame);
      found != robot.waiting.end()) {
    taken = std::move(*found);
  }
  std::erase_if(robot.waiting,
                [&](const Notice& waiting) { return waiting.frame.stamp_ns <= frame.stamp_ns; });
  return taken;
}

std::optional<std::vector<VisibleSegment>> LineSetHandler::visibilityAhead(
    const LineSetData& line_set, std::optional<Notice> notice,
    const std::shared_ptr<const PreparedMap>& map, const PoseWithCovariance& prior) {
  const bool same_view =
      notice && notice->map == map && notice->prior.pose.matrix() == prior.pose.matrix() &&
      notice->prior.covariance == prior.covariance && notice->camera == line_set.camera;
  if (!same_view) {
    return std::nullopt;
  }
  try {
    std::vector<VisibleSegment> visible = notice->visible.get();
    const std::lock_guard<std::mutex> lock(counters_mutex_);
    ++counters_.visibility_ahead;
    return visible;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace lineloc
