// Learning lines while serving, on a real PostGIS server: a robot's frames
// past a wall leave the window's edges as candidates of its pass (one robot,
// one day), which another robot or another day confirms and the same robot
// the same day does not; a tile left behind is written as it is left; frames
// beyond the queue or the frame interval are not taken; a piece the database
// cannot take is kept and written once it can.
#include <gtest/gtest.h>

#include <random>

#include "backbone/service/online_learning.h"
#include "db/citymodel/line_extraction.h"
#include "db/connection.h"
#include "db/enrichment_store.h"
#include "db/site.h"
#include "tests/support/test_database.h"
#include "tests/unit/backbone/enrichment/wall_drive.h"

namespace lineloc {
namespace {

using namespace wall_drive;

constexpr int64_t kSecond_ns = 1'000'000'000;
constexpr int64_t kDay_ns = 86'400 * kSecond_ns;
// 2026-04-12 12:00 UTC.
constexpr int64_t kNoon_ns = 1'775'995'200 * kSecond_ns;

class OnlineLearningTest : public ::testing::Test {
 protected:
  OnlineLearningTest() : database_("online_learning") {
    db::Connection owner(database_.conninfo());
    db::ensureSite(owner, "test", 7415, {85000.0, 447000.0, 0.0});
    building_id_ = std::stoll(
        owner
            .execParams("INSERT INTO building (site_id, source, source_id) SELECT id, 'test', "
                        "'wall' FROM site WHERE name = 'test' RETURNING id",
                        {})
            .text(0, 0));
    map_ = wallMap(building_id_);
    options_.db = database_.conninfo(test::DatabaseRole::kEnricher);
    options_.site = "test";
  }

  // The wall as a backbone's prepared map holds it: its face, of the
  // database's building, and the eave, a model line.
  static std::shared_ptr<const PreparedMap> wallMap(int64_t building_id) {
    auto tile = std::make_shared<MapTile>();
    db::ModelLine eave;
    eave.id = 1;
    eave.kind = citymodel::LineKind::kEave;
    eave.start_world = kEaveStart;
    eave.end_world = kEaveEnd;
    tile->lines.push_back(eave);
    tile->faces.push_back({1, building_id, 0, wallFaces()[0]});
    return std::make_shared<PreparedMap>(tile, Eigen::Vector3d(kWall_x, 5.0, 0.0));
  }

  // `robot`'s frames from y = 0, 0.5, ..., `period_ns` apart from `start_ns`,
  // answered OK at their true poses; among the lines visible from each, the
  // window's top as a learnt line, which must not keep it from being seen.
  void drive(OnlineLearning& learning, const std::string& robot, int64_t start_ns, int frames = 12,
             int64_t period_ns = kSecond_ns) {
    for (int k = 0; k < frames; ++k) {
      const EnrichmentFrame frame = frameAt(cameraAt(0.5 * k), 0.5, random_);
      LineSetData line_set;
      line_set.robot_id = robot;
      line_set.sequence_number = static_cast<uint32_t>(k);
      line_set.stamp_ns = start_ns + k * period_ns;
      line_set.camera = frame.camera;
      line_set.segments = frame.segments;
      std::vector<VisibleSegment> visible = frame.visible;
      VisibleSegment window_top;
      window_top.kind = static_cast<int>(citymodel::LineKind::kLearnt);
      window_top.start_world = kWindowTopStart;
      window_top.end_world = kWindowTopEnd;
      visible.push_back(window_top);
      learning.offer(line_set, frame.T_world_camera, map_, visible, std::nullopt);
    }
  }

  std::vector<db::StoredEnrichmentLine> stored() {
    db::Connection reader(database_.conninfo(test::DatabaseRole::kReader));
    return db::readEnrichment(reader, db::requireSite(reader, "test"));
  }

  test::TestDatabase database_;
  int64_t building_id_ = 0;
  std::shared_ptr<const PreparedMap> map_;
  OnlineLearningOptions options_;
  std::mt19937 random_{7};
};

TEST_F(OnlineLearningTest, ARobotsFramesLeaveTheWindowsEdgesAndAnotherRobotConfirmsThem) {
  OnlineLearning learning(options_, nullptr);
  drive(learning, "r1", kNoon_ns);
  learning.finishRobot("r1");
  learning.waitUntilIdle();
  std::vector<db::StoredEnrichmentLine> lines = stored();
  ASSERT_EQ(lines.size(), 3u);
  for (const db::StoredEnrichmentLine& line : lines) {
    EXPECT_EQ(line.status, db::EnrichmentStatus::kCandidate);
    EXPECT_EQ(line.building_id, building_id_);
    EXPECT_NEAR(line.start_world.x(), kWall_x, 1e-6);
    EXPECT_GT(std::abs(line.start_world.z() - kEaveStart.z()), 1.0) << "not the eave";
  }
  drive(learning, "r2", kNoon_ns + 3600 * kSecond_ns);
  learning.waitUntilIdle();
  learning.stop();
  lines = stored();
  ASSERT_EQ(lines.size(), 3u);
  for (const db::StoredEnrichmentLine& line : lines) {
    EXPECT_EQ(line.status, db::EnrichmentStatus::kConfirmed);
    EXPECT_EQ(line.passes, 2);
    EXPECT_EQ(line.robots, 2);
  }
  const LearningCounters counters = learning.counters();
  EXPECT_EQ(counters.frames, 24u);
  EXPECT_EQ(counters.pieces_written, 2u);
  EXPECT_EQ(counters.lines_added, 3u);
  EXPECT_EQ(counters.lines_seen_again, 3u);
  EXPECT_EQ(counters.lines_confirmed, 3u);
  EXPECT_EQ(counters.write_failures, 0u);
}

TEST_F(OnlineLearningTest, TheSameRobotConfirmsOnAnotherDayOnly) {
  OnlineLearning learning(options_, nullptr);
  drive(learning, "r1", kNoon_ns);
  learning.finishRobot("r1");
  drive(learning, "r1", kNoon_ns + 3600 * kSecond_ns);
  learning.finishRobot("r1");
  learning.waitUntilIdle();
  std::vector<db::StoredEnrichmentLine> lines = stored();
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].status, db::EnrichmentStatus::kCandidate);
  EXPECT_EQ(lines[0].passes, 1);
  drive(learning, "r1", kNoon_ns + kDay_ns);
  learning.waitUntilIdle();
  learning.stop();
  lines = stored();
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].status, db::EnrichmentStatus::kConfirmed);
  EXPECT_EQ(lines[0].passes, 2);
}

TEST_F(OnlineLearningTest, ATileLeftBehindIsWrittenAsItIsLeft) {
  // Tiles 4 m wide with a 1 m margin: the drive from y = 0 leaves the tile
  // [0, 4) at its frame at y = 5.5.
  options_.tile_size_m = 4.0;
  options_.tile_margin_m = 1.0;
  OnlineLearning learning(options_, nullptr);
  drive(learning, "r1", kNoon_ns);
  learning.waitUntilIdle();
  EXPECT_EQ(learning.counters().pieces_written, 1u);
  EXPECT_EQ(stored().size(), 3u);
}

TEST_F(OnlineLearningTest, FramesWithinTheIntervalOrBeyondTheQueueAreNotTaken) {
  OnlineLearning learning(options_, nullptr);
  // 30 Hz: one frame in four is 0.1 s after the last taken.
  drive(learning, "r1", kNoon_ns, 12, kSecond_ns / 30);
  learning.waitUntilIdle();
  EXPECT_EQ(learning.counters().frames, 3u);
  options_.max_queued_frames = 0;
  OnlineLearning full(options_, nullptr);
  drive(full, "r1", kNoon_ns);
  full.waitUntilIdle();
  EXPECT_EQ(full.counters().frames, 0u);
  EXPECT_EQ(full.counters().frames_dropped, 12u);
}

TEST_F(OnlineLearningTest, APieceTheDatabaseCannotTakeIsKeptAndWrittenOnceItCan) {
  options_.site = "later";
  OnlineLearning learning(options_, nullptr);
  drive(learning, "r1", kNoon_ns);
  learning.finishRobot("r1");
  learning.waitUntilIdle();
  EXPECT_EQ(learning.counters().write_failures, 1u);
  EXPECT_EQ(learning.counters().pieces_written, 0u);
  {
    db::Connection owner(database_.conninfo());
    db::ensureSite(owner, "later", 7415, {85000.0, 447000.0, 0.0});
  }
  drive(learning, "r2", kNoon_ns);
  learning.waitUntilIdle();
  learning.stop();
  EXPECT_EQ(learning.counters().pieces_written, 2u);
  db::Connection reader(database_.conninfo(test::DatabaseRole::kReader));
  const std::vector<db::StoredEnrichmentLine> lines =
      db::readEnrichment(reader, db::requireSite(reader, "later"));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].status, db::EnrichmentStatus::kConfirmed);
}

}  // namespace
}  // namespace lineloc
