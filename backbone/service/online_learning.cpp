#include "backbone/service/online_learning.h"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <utility>

#include "common/time/clock.h"
#include "db/citymodel/line_extraction.h"

namespace lineloc {
namespace {

bool learnt(int kind) {
  return kind == static_cast<int>(citymodel::LineKind::kLearnt);
}

// "<robot>/<YYYY-MM-DD>", the UTC day of `stamp_ns`.
std::string passOf(const std::string& robot_id, int64_t stamp_ns) {
  const std::time_t seconds = static_cast<std::time_t>(stamp_ns / 1'000'000'000);
  return fmt::format("{}/{:%Y-%m-%d}", robot_id, fmt::gmtime(seconds));
}

}  // namespace

OnlineLearning::OnlineLearning(const OnlineLearningOptions& options, ForegroundGate* gate)
    : options_(options),
      gate_(gate),
      frame_interval_ns_(static_cast<int64_t>(options.frame_interval_s * 1e9)),
      stale_track_ns_(static_cast<int64_t>(options.stale_track_s * 1e9)),
      failure_log_("enrichment write failures", 1, 10.0),
      thread_([this] { run(); }) {}

OnlineLearning::~OnlineLearning() {
  stop();
}

void OnlineLearning::offer(const LineSetData& line_set, const PoseWithCovariance& T_world_camera,
                           std::shared_ptr<const PreparedMap> map,
                           const std::vector<VisibleSegment>& visible,
                           const std::optional<Eigen::Vector3d>& towards_sun_world) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_) {
      return;
    }
    const auto last = last_taken_ns_.find(line_set.robot_id);
    if (last != last_taken_ns_.end() && line_set.stamp_ns >= last->second &&
        line_set.stamp_ns < last->second + frame_interval_ns_) {
      return;
    }
    if (queued_frames_ >= options_.max_queued_frames) {
      ++counters_.frames_dropped;
      return;
    }
    last_taken_ns_[line_set.robot_id] = line_set.stamp_ns;
    ++queued_frames_;
  }
  Frame taken;
  taken.map = std::move(map);
  EnrichmentFrame& frame = taken.frame;
  frame.robot_id = line_set.robot_id;
  frame.stamp_ns = line_set.stamp_ns;
  frame.camera = line_set.camera;
  frame.T_world_camera = T_world_camera;
  frame.segments = line_set.segments;
  frame.towards_sun_world = towards_sun_world;
  for (const VisibleSegment& segment : visible) {
    if (!learnt(segment.kind)) {
      frame.visible.push_back(segment);
    }
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    jobs_.push_back({line_set.robot_id, std::move(taken)});
  }
  changed_.notify_all();
}

void OnlineLearning::finishRobot(const std::string& robot_id) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_) {
      return;
    }
    last_taken_ns_.erase(robot_id);
    jobs_.push_back({robot_id, std::nullopt});
  }
  changed_.notify_all();
}

void OnlineLearning::stop() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_) {
      return;
    }
    stopping_ = true;
    counters_.frames_dropped += queued_frames_;
    std::erase_if(jobs_, [](const Job& job) { return job.frame.has_value(); });
    queued_frames_ = 0;
  }
  changed_.notify_all();
  thread_.join();
}

void OnlineLearning::waitUntilIdle() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return jobs_.empty() && !running_job_; });
}

LearningCounters OnlineLearning::counters() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

void OnlineLearning::run() {
  const BackgroundOf background(gate_);
  while (true) {
    Job job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [this] { return !jobs_.empty() || stopping_; });
      if (jobs_.empty()) {
        break;
      }
      job = std::move(jobs_.front());
      jobs_.pop_front();
      queued_frames_ -= job.frame ? 1 : 0;
      running_job_ = true;
    }
    if (gate_ != nullptr) {
      gate_->yieldToForeground();
    }
    try {
      if (job.frame) {
        learn(job.robot_id, std::move(*job.frame));
      } else if (const auto robot = robots_.find(job.robot_id); robot != robots_.end()) {
        finish(robot->second, job.robot_id);
        robots_.erase(robot);
      }
    } catch (const std::exception& error) {
      spdlog::error("learning from {}'s frames failed: {}", job.robot_id, error.what());
    }
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      running_job_ = false;
    }
    changed_.notify_all();
  }
  for (auto& [robot_id, robot] : robots_) {
    finish(robot, robot_id);
  }
  robots_.clear();
}

Eigen::AlignedBox2d OnlineLearning::tileBounds(const TileKey& tile, double margin_m) const {
  const Eigen::Vector2d corner(static_cast<double>(tile.x) * options_.tile_size_m,
                               static_cast<double>(tile.y) * options_.tile_size_m);
  return {corner - Eigen::Vector2d::Constant(margin_m),
          corner + Eigen::Vector2d::Constant(options_.tile_size_m + margin_m)};
}

bool OnlineLearning::outsideTile(const RobotLearning& robot,
                                 const Eigen::Vector3d& position_world) const {
  return !tileBounds(robot.tile, options_.tile_margin_m).contains(position_world.head<2>());
}

void OnlineLearning::start(RobotLearning& robot, const std::string& robot_id,
                           const EnrichmentFrame& frame) {
  const Eigen::Vector3d position = frame.T_world_camera.pose.translation();
  robot.tile = {static_cast<int64_t>(std::floor(position.x() / options_.tile_size_m)),
                static_cast<int64_t>(std::floor(position.y() / options_.tile_size_m))};
  robot.pass = passOf(robot_id, frame.stamp_ns);
  std::vector<KnownLearntLine> known;
  try {
    known = store().knownLines(
        tileBounds(robot.tile, options_.tile_margin_m + options_.learner.expected.max_depth_m));
  } catch (const std::exception& error) {
    store_.reset();
    failure_log_.log(fmt::format(
        "the stored learnt lines around {} could not be read, so none is expected of it: {}",
        robot_id, error.what()));
  }
  robot.learner.emplace(std::move(known), options_.learner);
  robot.maps.clear();
}

void OnlineLearning::learn(const std::string& robot_id, Frame frame) {
  RobotLearning& robot = robots_[robot_id];
  const Eigen::Vector3d position = frame.frame.T_world_camera.pose.translation();
  if (robot.learner && outsideTile(robot, position)) {
    finish(robot, robot_id);
  }
  if (!robot.learner) {
    start(robot, robot_id, frame.frame);
  }
  robot.learner->observe(frame.frame, frame.map->scene);
  if (std::ranges::find(robot.maps, frame.map) == robot.maps.end()) {
    robot.maps.push_back(std::move(frame.map));
  }
  robot.learner->forgetStaleTracks(frame.frame.stamp_ns - stale_track_ns_);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.frames;
  }
  if (robot.learner->heldViews() > options_.max_views_per_robot) {
    finish(robot, robot_id);
  }
}

void OnlineLearning::finish(RobotLearning& robot, const std::string& robot_id) {
  if (!robot.learner) {
    return;
  }
  std::vector<ModelSegment> model_lines;
  for (const std::shared_ptr<const PreparedMap>& map : robot.maps) {
    for (const ModelSegment& line : map->segments) {
      if (!learnt(line.kind)) {
        model_lines.push_back(line);
      }
    }
  }
  LearntPass learnt_pass = robot.learner->finish(model_lines);
  robot.learner.reset();
  robot.maps.clear();
  if (!learnt_pass.lines.empty() || !learnt_pass.expected.empty()) {
    pending_.push_back({robot.pass, robot_id, std::move(learnt_pass)});
    if (pending_.size() > options_.max_pending_pieces) {
      pending_.pop_front();
      const std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.pieces_dropped;
    }
  }
  writePending();
}

void OnlineLearning::writePending() {
  while (!pending_.empty()) {
    const Piece& piece = pending_.front();
    db::EnrichmentWriteReport report;
    try {
      report = store().write(piece.pass, piece.robot_id, piece.learnt);
    } catch (const std::exception& error) {
      store_.reset();
      failure_log_.log(fmt::format("pass '{}' could not be written ({} kept to try again): {}",
                                   piece.pass, pending_.size(), error.what()));
      const std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.write_failures;
      return;
    }
    spdlog::info(
        "learnt lines of pass '{}': {} new candidates, {} lines seen again ({} confirmed by it), "
        "{} seen in the pass before; {} expected lines missed ({} retired)",
        piece.pass, report.added, report.joined, report.confirmed, report.already_written,
        report.missed, report.retired);
    pending_.pop_front();
    const std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.pieces_written;
    counters_.lines_added += static_cast<uint64_t>(report.added);
    counters_.lines_seen_again += static_cast<uint64_t>(report.joined);
    counters_.lines_confirmed += static_cast<uint64_t>(report.confirmed);
    counters_.lines_missed += static_cast<uint64_t>(report.missed);
    counters_.lines_retired += static_cast<uint64_t>(report.retired);
  }
}

EnrichmentPassStore& OnlineLearning::store() {
  if (!store_) {
    store_.emplace(options_.db, options_.site, true);
  }
  return *store_;
}

}  // namespace lineloc
