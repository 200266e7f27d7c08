#include "backbone/service/line_set_handler.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/time/clock.h"

namespace lineloc {

lineloc_msg_FixStatus toFixStatus(AlignmentStatus status) {
  switch (status) {
    case AlignmentStatus::kOk:
      return lineloc_msg_FIX_OK;
    case AlignmentStatus::kTooFewMatches:
      return lineloc_msg_FIX_TOO_FEW_MATCHES;
    case AlignmentStatus::kIllConditioned:
      return lineloc_msg_FIX_DEGENERATE;
    case AlignmentStatus::kAmbiguous:
      return lineloc_msg_FIX_AMBIGUOUS;
    case AlignmentStatus::kFailed:
    case AlignmentStatus::kInconsistent:
      return lineloc_msg_FIX_DIVERGED;
  }
  return lineloc_msg_FIX_INTERNAL_ERROR;
}

LineSetHandler::LineSetHandler(MapTileCache& map, const MessageLimits& limits,
                               const PipelineOptions& options)
    : map_(map),
      limits_(limits),
      options_(options),
      silence_ns_(static_cast<int64_t>(options.forget_robot_after_s * 1e9)),
      proof_reach_{options.proof_position_sigma_m, options.confirm_rotation_rad},
      foreground_(fromMilliseconds(options.max_background_yield_ms)),
      cadence_(fromMilliseconds(options.quiet_before_frame_ms),
               fromMilliseconds(options.max_background_yield_ms)),
      maps_(map, options.query_radius_m, options.map_reuse_distance_m, &foreground_),
      search_worker_(&foreground_) {}

void LineSetHandler::waitForSearches() {
  maps_.waitUntilIdle();
  search_worker_.waitUntilIdle();
}

BackboneCounters LineSetHandler::counters() const {
  const std::lock_guard<std::mutex> lock(counters_mutex_);
  return counters_;
}

namespace {

const std::string& robotIdOf(const std::string& robot_id) {
  return robot_id;
}

template <typename Entry>
const std::string& robotIdOf(const std::pair<const std::string, Entry>& entry) {
  return entry.first;
}

// Erases the entries of `table`, a map or set keyed by robot id, whose robot
// `unheard` names.
template <typename Table, typename Unheard>
void eraseRobots(Table& table, const Unheard& unheard) {
  std::erase_if(table, [&](const auto& entry) { return unheard(robotIdOf(entry)); });
}

}  // namespace

void LineSetHandler::hearFrom(const std::string& robot_id, int64_t arrival_ns) {
  forgetSilentRobotsWhenDue(arrival_ns);
  if (!last_heard_ns_.insert_or_assign(robot_id, arrival_ns).second) {
    return;
  }
  const std::lock_guard<std::mutex> lock(counters_mutex_);
  counters_.robots = last_heard_ns_.size();
}

void LineSetHandler::forgetSilentRobotsWhenDue(int64_t now_ns) {
  if (now_ns < next_forgetting_ns_) {
    return;
  }
  next_forgetting_ns_ = now_ns + silence_ns_ / 2;
  forgetSilentRobots(now_ns);
}

void LineSetHandler::forgetSilentRobots(int64_t now_ns) {
  const uint64_t forgotten = std::erase_if(last_heard_ns_, [&](const auto& robot) {
    const int64_t silent_ns = now_ns - robot.second;
    if (silent_ns <= silence_ns_) {
      return false;
    }
    spdlog::info("forgetting robot {}: not heard from for {:.1f} s", robot.first, silent_ns * 1e-9);
    return true;
  });
  forgetUnheardRobots();
  const std::lock_guard<std::mutex> lock(counters_mutex_);
  counters_.robots = last_heard_ns_.size();
  counters_.robots_forgotten += forgotten;
}

void LineSetHandler::forgetUnheardRobots() {
  const auto unheard = [this](const std::string& robot_id) {
    return !last_heard_ns_.contains(robot_id);
  };
  eraseRobots(last_position_, unheard);
  eraseRobots(motion_, unheard);
  eraseRobots(fix_scatter_, unheard);
  cadence_.forget(unheard);
  {
    const std::lock_guard<std::mutex> lock(searches_mutex_);
    eraseRobots(acquisition_, unheard);
    eraseRobots(tracking_start_, unheard);
    eraseRobots(searching_again_, unheard);
  }
  const std::lock_guard<std::mutex> lock(notices_mutex_);
  eraseRobots(notices_, unheard);
}

void LineSetHandler::prefetchAlongMotion(const LineSetData& line_set) {
  const Eigen::Vector3d position = line_set.predicted_T_world_camera.pose.translation();
  const auto last = last_position_.find(line_set.robot_id);
  if (last != last_position_.end() && line_set.stamp_ns > last->second.stamp_ns) {
    const double dt_s = (line_set.stamp_ns - last->second.stamp_ns) * 1e-9;
    const Eigen::Vector3d velocity = (position - last->second.position) / dt_s;
    map_.prefetch(position + velocity * options_.prefetch_lookahead_s, options_.query_radius_m);
  }
  last_position_[line_set.robot_id] = {line_set.stamp_ns, position};
}

PoseWithCovariance LineSetHandler::groundedPrior(const LineSetData& line_set,
                                                 const PreparedMap& map) const {
  PoseWithCovariance prior = line_set.predicted_T_world_camera;
  const double ground_variance = options_.ground_level_sigma_m * options_.ground_level_sigma_m;
  const std::optional<double> ground_level =
      map.ground_level.at(prior.pose.translation().head<2>());
  if (line_set.camera_height_m <= 0.0 || !ground_level ||
      !(prior.covariance(2, 2) > ground_variance)) {
    return prior;
  }
  prior.pose.translation().z() = *ground_level + line_set.camera_height_m;
  prior.covariance.row(2).setZero();
  prior.covariance.col(2).setZero();
  prior.covariance(2, 2) = ground_variance;
  return prior;
}

PoseWithCovariance LineSetHandler::trackingPrior(const LineSetData& line_set,
                                                 const PreparedMap& map) {
  return searchPrior(line_set.robot_id, groundedPrior(line_set, map));
}

std::optional<Sunlight> sunlightAt(const PipelineOptions& options, int64_t stamp_ns) {
  if (options.sun_from_clock) {
    return options.sun_from_clock->at(stamp_ns);
  }
  return options.localizer.visibility.sunlight;
}

LocalizerOptions LineSetHandler::localizerOptions(const LineSetData& line_set) const {
  LocalizerOptions options = options_.localizer;
  options.visibility.sunlight = sunlightAt(options_, line_set.stamp_ns);
  return options;
}

void LineSetHandler::track(const LineSetData& line_set, const OdometryPose& odometry,
                           const std::shared_ptr<const PreparedMap>& map,
                           const PoseWithCovariance& prior, const LocalizerOptions& options,
                           PoseFixData& fix,
                           const std::vector<VisibleSegment>* visible_from_prior) {
  const Localization localization =
      localize(line_set.segments, line_set.corners, map->segments, map->scene, prior,
               line_set.camera, options, visible_from_prior);
  const Alignment& alignment = localization.alignment;
  fix.timings.visibility += localization.visibility_ns;
  fix.timings.matching = alignment.matching_ns;
  fix.timings.pose = alignment.pose_ns;
  fix.status = toFixStatus(alignment.status);
  fix.inliers = static_cast<uint32_t>(alignment.inliers);
  fix.residual_rms_px = static_cast<float>(alignment.rms_residual_px);
  if (alignment.status != AlignmentStatus::kOk) {
    return;
  }
  fix.T_world_camera =
      fix_scatter_.try_emplace(line_set.robot_id, options_.fix_scatter)
          .first->second.floorAndAdd(line_set.stamp_ns, odometry, alignment.T_world_camera);
  widenUntilProven(line_set, odometry, map, fix);
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

// The poses a search found: its best, and an ambiguous search's rival too.
std::vector<Eigen::Isometry3d> foundPoses(const Localization& found) {
  std::vector<Eigen::Isometry3d> poses{found.alignment.T_world_camera.pose};
  if (found.alignment.status == AlignmentStatus::kAmbiguous && found.search &&
      found.search->T_world_camera_rival) {
    poses.push_back(*found.search->T_world_camera_rival);
  }
  return poses;
}

}  // namespace

void LineSetHandler::search(const LineSetData& line_set, const OdometryPose& odometry,
                            std::shared_ptr<const PreparedMap> map,
                            const PoseWithCovariance& prior) {
  const int64_t start_ns = steadyClockNs();
  std::shared_ptr<AcquisitionSession> session;
  {
    const std::lock_guard<std::mutex> lock(searches_mutex_);
    auto& own = acquisition_[line_set.robot_id];
    if (!own) {
      own = std::make_shared<AcquisitionSession>(options_.hypotheses);
    }
    session = own;
  }
  const AcquisitionSession::Searched searched =
      session->search(line_set, odometry, std::move(map), prior, localizerOptions(line_set));
  const int64_t search_ns = steadyClockNs() - start_ns;
  countSearch();
  const Alignment& alignment = searched.acquisition.alignment;
  std::string outcome = alignment.message.empty() ? "" : alignment.message + "; ";
  outcome += fmt::format("{} hypotheses kept", searched.hypotheses);
  if (searched.decision) {
    startTrackingFrom(line_set, odometry, *searched.decision);
    session->clear();
    outcome += fmt::format(
        "; takes one at {} with posterior {:.4f}, covering rivals up to {:.2f} m and {:.2f} deg: "
        "tracking",
        describePose(searched.decision->hypothesis.T_world_camera.pose),
        searched.decision->posterior, searched.decision->covered.position_m,
        searched.decision->covered.rotation_rad * 180.0 / M_PI);
  }
  logSearch("search", line_set, alignment, searched.acquisition.summary, outcome, search_ns);
}

void LineSetHandler::startTrackingFrom(const LineSetData& line_set, const OdometryPose& odometry,
                                       const HypothesisDecision& decision) {
  const PoseWithCovariance& found = decision.hypothesis.T_world_camera;
  // A pose too wide to track from is tracked within the tracking limits; its
  // own width is then part of what the fixes leave unproven.
  PoseOffset unproven = decision.covered;
  if (needsAcquisition(found, options_.localizer)) {
    unproven = unproven.farthest(
        {largestPositionSigma(found.covariance), std::sqrt(std::max(0.0, found.covariance(5, 5)))});
  }
  const std::lock_guard<std::mutex> lock(searches_mutex_);
  tracking_start_.insert_or_assign(
      line_set.robot_id,
      TrackingStart{
          .origin = {line_set.stamp_ns, found, odometry}, .searched = true, .rival = unproven});
  searching_again_.erase(line_set.robot_id);
}

LineSetHandler::ProofVerdict LineSetHandler::judgeProof(const LineSetData& line_set,
                                                        const PreparedMap& map,
                                                        const Eigen::Isometry3d& tracked,
                                                        const Localization& found) const {
  const Alignment& alignment = found.alignment;
  const bool ambiguous = alignment.status == AlignmentStatus::kAmbiguous;
  if (alignment.status != AlignmentStatus::kOk && !ambiguous) {
    return {Proof::kUndecided, alignment.message + "; tried again later", {}};
  }
  if (!ambiguous && agrees(tracked, alignment.T_world_camera.pose)) {
    return {Proof::kAgrees, "agrees with tracking", {}};
  }
  const AcquisitionOptions& acquisition = options_.localizer.acquisition;
  const auto score = [&](const Eigen::Isometry3d& T_world_camera) {
    return verificationScore(line_set.segments, map.segments, map.scene, T_world_camera,
                             line_set.camera, acquisition);
  };
  const double tracked_score = score(tracked);
  const double fraction = acquisition.ambiguous_score_fraction;
  ProofVerdict verdict{Proof::kUndecided, ambiguous ? alignment.message + "; " : "", {}};
  for (const Eigen::Isometry3d& pose : foundPoses(found)) {
    if (agrees(tracked, pose)) {
      continue;
    }
    const double found_score = score(pose);
    const PoseOffset offset = PoseOffset::between(tracked, pose);
    verdict.outcome +=
        fmt::format("finds a pose {:.2f} m from tracking, which scores {:.1f} to its {:.1f}; ",
                    offset.position_m, tracked_score, found_score);
    if (!ambiguous && tracked_score < fraction * found_score) {
      verdict.proof = Proof::kContradicts;
      verdict.outcome += "tracking stops; the robot is searched for again";
      return verdict;
    }
    if (found_score >= fraction * tracked_score) {
      verdict.rival = verdict.rival.farthest(offset);
    }
  }
  if (verdict.rival.position_m > 0.0) {
    verdict.outcome += "its rival widens the fixes until tracking is proven; ";
  }
  verdict.outcome += "tried again later";
  return verdict;
}

void LineSetHandler::prove(const LineSetData& line_set, const PreparedMap& map,
                           const Eigen::Isometry3d& tracked, const SearchResult& origin,
                           double moved_m) {
  const int64_t start_ns = steadyClockNs();
  PoseWithCovariance prior{tracked, diagonalPoseCovariance(options_.proof_position_sigma_m,
                                                           options_.confirm_rotation_rad)};
  prior.covariance(2, 2) = options_.ground_level_sigma_m * options_.ground_level_sigma_m;
  const Localization localization =
      localize(line_set.segments, line_set.corners, map.segments, map.scene, prior, line_set.camera,
               localizerOptions(line_set));
  ProofVerdict verdict = judgeProof(line_set, map, tracked, localization);
  const int64_t search_ns = steadyClockNs() - start_ns;
  countSearch();
  {
    const std::lock_guard<std::mutex> lock(searches_mutex_);
    const auto start = tracking_start_.find(line_set.robot_id);
    if (start == tracking_start_.end() || !start->second.startedAt(origin)) {
      verdict.outcome += "; dropped, as the robot no longer tracks from the start it judged";
    } else if (verdict.proof == Proof::kContradicts) {
      tracking_start_.erase(start);
      searching_again_.insert(line_set.robot_id);
    } else {
      TrackingStart& tracking = start->second;
      const bool from_elsewhere = moved_m >= options_.acquisition_proven_after_m;
      tracking.agreeing_proofs += verdict.proof == Proof::kAgrees && from_elsewhere ? 1 : 0;
      tracking.rival = tracking.rival.farthest(verdict.rival);
      tracking.looked_around |= localization.alignment.status == AlignmentStatus::kOk ||
                                localization.alignment.status == AlignmentStatus::kAmbiguous;
      tracking.proof_due_m =
          std::max(moved_m + options_.proof_retry_m, options_.acquisition_proven_after_m);
    }
  }
  logSearch("proof search", line_set, localization.alignment,
            localization.search.value_or(SearchSummary{}), verdict.outcome, search_ns);
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

std::optional<PoseWithCovariance> LineSetHandler::movedByOdometry(const SearchResult& search,
                                                                  const OdometryPose& odometry) {
  if (search.odometry.epoch != odometry.epoch) {
    return std::nullopt;
  }
  return composeExactMotion(search.T_world_camera_found,
                            search.odometry.T_odom_camera.inverse() * odometry.T_odom_camera);
}

bool LineSetHandler::agrees(const Eigen::Isometry3d& expected,
                            const Eigen::Isometry3d& found) const {
  return PoseOffset::between(expected, found)
      .within({options_.confirm_position_m, options_.confirm_rotation_rad});
}

std::optional<PoseWithCovariance> LineSetHandler::carriedSearch(const LineSetData& line_set,
                                                                const OdometryPose& odometry) {
  const std::lock_guard<std::mutex> lock(searches_mutex_);
  const auto start = tracking_start_.find(line_set.robot_id);
  if (start == tracking_start_.end() || !start->second.searched) {
    return std::nullopt;
  }
  const SearchResult& search = start->second.origin;
  const double age_s = (line_set.stamp_ns - search.stamp_ns) * 1e-9;
  if (!(age_s > 0.0 && age_s <= options_.carry_search_s)) {
    return std::nullopt;
  }
  const std::optional<PoseWithCovariance> carried = movedByOdometry(search, odometry);
  if (!carried) {
    return std::nullopt;
  }
  return narrowedForTracking(*carried, options_.localizer);
}

void LineSetHandler::widenUntilProven(const LineSetData& line_set, const OdometryPose& odometry,
                                      const std::shared_ptr<const PreparedMap>& map,
                                      PoseFixData& fix) {
  if (fix.status != lineloc_msg_FIX_OK) {
    return;
  }
  bool proof_due = false;
  double moved_m = 0.0;
  PoseOffset rival;
  SearchResult origin;
  {
    const std::lock_guard<std::mutex> lock(searches_mutex_);
    auto start = tracking_start_.find(line_set.robot_id);
    if (start == tracking_start_.end() || start->second.origin.odometry.epoch != odometry.epoch) {
      start = tracking_start_
                  .insert_or_assign(
                      line_set.robot_id,
                      TrackingStart{.origin = {line_set.stamp_ns, fix.T_world_camera, odometry}})
                  .first;
      spdlog::info(
          "tracking {} from #{} on from its own prediction, which no search here found: its "
          "fixes stay widened until proof searches agree",
          line_set.robot_id, line_set.sequence_number);
    }
    const TrackingStart& tracking = start->second;
    if (tracking.agreeing_proofs >= options_.agreeing_proofs_needed) {
      return;
    }
    moved_m = (odometry.T_odom_camera.translation() -
               tracking.origin.odometry.T_odom_camera.translation())
                  .norm();
    proof_due = moved_m >= tracking.proof_due_m;
    rival = tracking.looked_around ? tracking.rival : tracking.rival.farthest(proof_reach_);
    origin = tracking.origin;
  }
  if (proof_due) {
    submitSearch("proof search", line_set,
                 [this, line_set, map, tracked = fix.T_world_camera.pose, origin, moved_m] {
                   prove(line_set, *map, tracked, origin, moved_m);
                 });
  }
  const AcquisitionOptions& acquisition = options_.localizer.acquisition;
  fix.unproven_position_sigma_m = std::max(acquisition.acquired_position_sigma_m, rival.position_m);
  fix.unproven_rotation_sigma_rad =
      std::max(acquisition.acquired_rotation_sigma_rad, rival.rotation_rad);
  fix.T_world_camera.covariance +=
      diagonalPoseCovariance(fix.unproven_position_sigma_m, fix.unproven_rotation_sigma_rad);
}

PoseWithCovariance LineSetHandler::searchPrior(const std::string& robot_id,
                                               const PoseWithCovariance& prior) {
  const std::lock_guard<std::mutex> lock(searches_mutex_);
  if (!searching_again_.contains(robot_id)) {
    return prior;
  }
  PoseWithCovariance widened = prior;
  const double floor_variance = options_.proof_position_sigma_m * options_.proof_position_sigma_m;
  for (int axis = 0; axis < 2; ++axis) {
    widened.covariance(axis, axis) = std::max(widened.covariance(axis, axis), floor_variance);
  }
  return widened;
}

void LineSetHandler::submitSearch(const char* kind, const LineSetData& line_set,
                                  std::function<void()> run) {
  search_worker_.submit(
      line_set.robot_id, [kind, robot_id = line_set.robot_id, sequence = line_set.sequence_number,
                          run = std::move(run)] {
        try {
          run();
        } catch (const std::exception& error) {
          spdlog::error("{} for {} #{} failed: {}", kind, robot_id, sequence, error.what());
        }
      });
}

void LineSetHandler::countSearch() {
  const std::lock_guard<std::mutex> lock(counters_mutex_);
  ++counters_.searches;
}

void LineSetHandler::announceNextFrame(const PoseFixData& fix, int64_t arrival_ns) {
  const bool tracked = fix.status != lineloc_msg_FIX_NO_MATCH_COMPUTED &&
                       fix.status != lineloc_msg_FIX_NO_MAP_LINES &&
                       fix.status != lineloc_msg_FIX_INTERNAL_ERROR;
  cadence_.add(fix.robot_id, fix.stamp_ns, arrival_ns, tracked);
  foreground_.expectForegroundFrom(cadence_.quietFrom_ns(steadyClockNs()));
}

PoseFixData LineSetHandler::finish(PoseFixData fix, int64_t start_ns) {
  announceNextFrame(fix, start_ns);
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
  const ForegroundGate::Scope foreground(foreground_);
  const int64_t start_ns = steadyClockNs();
  {
    const std::lock_guard<std::mutex> lock(counters_mutex_);
    ++counters_.received;
  }
  if (const std::optional<std::string> error = findLineSetError(message, limits_)) {
    countDrop("LineSet", message.sequence_number, *error);
    return std::nullopt;
  }
  const LineSetData line_set = fromMessage(message);
  hearFrom(line_set.robot_id, start_ns);
  std::optional<Notice> notice = takeNotice(line_set);
  const OdometryPose odometry =
      motion_.try_emplace(line_set.robot_id, options_.motion)
          .first->second.add(line_set.stamp_ns, line_set.predicted_T_world_camera);
  PoseFixData fix;
  fix.robot_id = line_set.robot_id;
  fix.sequence_number = line_set.sequence_number;
  fix.stamp_ns = line_set.stamp_ns;
  fix.T_world_camera = line_set.predicted_T_world_camera;
  try {
    const std::shared_ptr<const PreparedMap> map =
        maps_.around(line_set.predicted_T_world_camera.pose.translation());
    fix.timings.map = steadyClockNs() - start_ns;
    prefetchAlongMotion(line_set);
    if (!map) {
      fix.status = lineloc_msg_FIX_NO_MATCH_COMPUTED;
      return finish(fix, start_ns);
    }
    fix.model_lines = static_cast<uint32_t>(map->view->lines.size());
    if (map->view->lines.empty()) {
      fix.status = lineloc_msg_FIX_NO_MAP_LINES;
      return finish(fix, start_ns);
    }
    const PoseWithCovariance prior = trackingPrior(line_set, *map);
    if (!needsAcquisition(prior, options_.localizer)) {
      const int64_t waiting_start_ns = steadyClockNs();
      const std::optional<std::vector<VisibleSegment>> ahead =
          visibilityAhead(line_set, std::move(notice), map, prior);
      fix.timings.visibility = ahead ? steadyClockNs() - waiting_start_ns : 0;
      track(line_set, odometry, map, prior, localizerOptions(line_set), fix,
            ahead ? &*ahead : nullptr);
      return finish(fix, start_ns);
    }
    if (const std::optional<PoseWithCovariance> carried = carriedSearch(line_set, odometry)) {
      LocalizerOptions from_search = localizerOptions(line_set);
      from_search.min_start_step_m = options_.carried_start_step_m;
      track(line_set, odometry, map, *carried, from_search, fix);
      return finish(fix, start_ns);
    }
    submitSearch("search", line_set, [this, line_set, odometry, map, prior] {
      search(line_set, odometry, map, prior);
    });
    fix.status = lineloc_msg_FIX_NO_MATCH_COMPUTED;
  } catch (const std::exception& error) {
    spdlog::error("map for {} #{} failed: {}", fix.robot_id, fix.sequence_number, error.what());
    const std::lock_guard<std::mutex> lock(counters_mutex_);
    ++counters_.map_errors;
    fix.status = lineloc_msg_FIX_INTERNAL_ERROR;
  }
  return finish(fix, start_ns);
}

void LineSetHandler::countDrop(const char* kind, uint32_t sequence_number,
                               const std::string& error) {
  spdlog::warn("dropped {} #{}: {}", kind, sequence_number, error);
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
  const LineSetData exposure = fromMessage(message);
  std::promise<std::vector<VisibleSegment>> visible;
  try {
    const std::shared_ptr<const PreparedMap> map =
        maps_.preparedAround(exposure.predicted_T_world_camera.pose.translation());
    if (!map || map->view->lines.empty()) {
      return;
    }
    const PoseWithCovariance prior = trackingPrior(exposure, *map);
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
