// Learning lines while serving (paper §3.1: the database is enriched "also
// during use, by processing images from the camera on the robot"): the frames
// a backbone answers OK feed, per robot, the learner lineloc-enrich runs on a
// recorded drive (backbone/enrichment/line_learner.h), and what it learns is
// written to the site's enrichment (db/enrichment_store.h) as the enricher
// role.
//
// Frames. A frame answered OK is offered with its fix, the map it was
// localized in and the model lines visible from its prior. One offered within
// frame_interval_s of its robot's last taken is skipped: at 30 Hz consecutive
// frames add views, hardly baseline. Taken frames wait for the learning
// thread, at most max_queued_frames in all; one beyond is dropped and
// counted. The thread is background work of the backbone's gate
// (foreground_gate.h): it learns while no LineSet is being answered.
//
// Passes. A pass is one robot's frames of one UTC day, named
// "<robot>/<YYYY-MM-DD>" (a piece by the day of its first frame): another
// robot, or the same robot on another day, confirms a line
// (db/enrichment_store.h), a robot that drives a street twice in a day does
// not confirm what it saw alone, and a robot handed over to another
// backbone, or served again after a restart, goes on with its pass.
//
// Tiles. A robot learns in the square tile of tile_size_m its camera is in,
// reading the stored lines it may be expected to see around it; once its
// camera is more than tile_margin_m outside the tile, what it learnt there is
// written, a piece of its pass, and it learns in the tile it is in. Memory
// per robot is one tile's tracks: those too short to triangulate are
// forgotten stale_track_s after their last view, and a learner that holds
// max_views_per_robot views all the same writes its piece early. A robot the
// backbone forgets (silent, or left to another backbone) has its piece
// written; stopping writes every robot's.
//
// Writes. A piece the database cannot take is kept, at most
// max_pending_pieces (the oldest dropped beyond, counted), and tried again
// before the next; each write is one transaction, so what is stored is never
// half written. Stopping tries once more: give the connection string a
// connect_timeout so that a backbone stops promptly while its database is
// down.
#pragma once

#include <Eigen/Core>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "backbone/enrichment/enrichment_pass_store.h"
#include "backbone/enrichment/line_learner.h"
#include "backbone/service/prepared_maps.h"
#include "common/logging/rate_limited_log.h"
#include "common/messages/messages.h"
#include "common/parallel/foreground_gate.h"

namespace lineloc {

struct OnlineLearningOptions {
  // The enricher role's libpq connection string; empty: no learning.
  std::string db;
  std::string site;
  double frame_interval_s = 0.1;
  double tile_size_m = 100.0;
  double tile_margin_m = 20.0;
  double stale_track_s = 10.0;
  size_t max_views_per_robot = 20000;
  size_t max_queued_frames = 64;
  size_t max_pending_pieces = 16;
  LineLearnerOptions learner;
};

struct LearningCounters {
  uint64_t frames = 0;          // frames learnt from
  uint64_t frames_dropped = 0;  // taken frames the queue had no room for
  uint64_t pieces_written = 0;
  uint64_t pieces_dropped = 0;  // beyond max_pending_pieces
  uint64_t write_failures = 0;
  // Of the pieces written: lines added as candidates, sightings of stored
  // lines, lines they confirmed, expected lines missed and lines retired.
  uint64_t lines_added = 0;
  uint64_t lines_seen_again = 0;
  uint64_t lines_confirmed = 0;
  uint64_t lines_missed = 0;
  uint64_t lines_retired = 0;
};

class OnlineLearning {
 public:
  // `gate` (may be null) must outlive this.
  OnlineLearning(const OnlineLearningOptions& options, ForegroundGate* gate);
  // stop().
  ~OnlineLearning();
  OnlineLearning(const OnlineLearning&) = delete;
  OnlineLearning& operator=(const OnlineLearning&) = delete;

  // A frame answered OK (see above). `visible`: the lines visible from its
  // prior; the learnt ones among them are left out, so that a learnt line is
  // learnt again where it is seen. Safe to call from several threads.
  void offer(const LineSetData& line_set, const PoseWithCovariance& T_world_camera,
             std::shared_ptr<const PreparedMap> map, const std::vector<VisibleSegment>& visible,
             const std::optional<Eigen::Vector3d>& towards_sun_world);

  // Writes `robot_id`'s piece, after the frames of it already taken.
  void finishRobot(const std::string& robot_id);

  // Drops the frames waiting (counted), writes every robot's piece and ends
  // the thread.
  void stop();

  // Blocks until the frames taken and the pieces asked for are written.
  void waitUntilIdle();

  LearningCounters counters() const;

 private:
  struct Frame {
    EnrichmentFrame frame;
    std::shared_ptr<const PreparedMap> map;
  };
  struct Job {
    std::string robot_id;
    std::optional<Frame> frame;  // none: finish the robot's piece
  };
  struct TileKey {
    int64_t x = 0;
    int64_t y = 0;
  };
  // What one robot learns in its tile, on the learning thread.
  struct RobotLearning {
    std::string pass;
    TileKey tile;
    std::optional<LineLearner> learner;
    // The maps its frames were localized in, whose model lines the learnt
    // lines must not repeat.
    std::vector<std::shared_ptr<const PreparedMap>> maps;
  };
  struct Piece {
    std::string pass;
    std::string robot_id;
    LearntPass learnt;
  };

  void run();
  void learn(const std::string& robot_id, Frame frame);
  // Starts `robot`'s learner in the tile at `position_world`.
  void start(RobotLearning& robot, const std::string& robot_id, const EnrichmentFrame& frame);
  bool outsideTile(const RobotLearning& robot, const Eigen::Vector3d& position_world) const;
  Eigen::AlignedBox2d tileBounds(const TileKey& tile, double margin_m) const;
  // Queues what `robot` learnt for writing and writes what is queued.
  void finish(RobotLearning& robot, const std::string& robot_id);
  void writePending();
  // The store, connected when it is not.
  EnrichmentPassStore& store();

  const OnlineLearningOptions options_;
  ForegroundGate* const gate_;
  const int64_t frame_interval_ns_;
  const int64_t stale_track_ns_;

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> jobs_;
  size_t queued_frames_ = 0;
  bool running_job_ = false;
  bool stopping_ = false;
  std::map<std::string, int64_t> last_taken_ns_;
  LearningCounters counters_;

  // The learning thread's own.
  std::map<std::string, RobotLearning> robots_;
  std::deque<Piece> pending_;
  std::optional<EnrichmentPassStore> store_;
  RateLimitedLog failure_log_;

  std::thread thread_;
};

}  // namespace lineloc
