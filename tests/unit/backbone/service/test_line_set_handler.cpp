// The backbone's per-message handling against a real PostGIS database.
#include <gtest/gtest.h>

#include <limits>
#include <memory>

#include "backbone/service/line_set_handler.h"
#include "tests/support/test_database.h"

namespace lineloc {
namespace {

std::unique_ptr<LineSetMessage> validMessage(const Eigen::Vector3d& position) {
  LineSetData data;
  data.robot_id = "handler-test";
  data.sequence_number = 3;
  data.stamp_ns = 1'000'000;
  data.camera = {500, 500, 320, 240, 0, 640, 480};
  data.segments.resize(4);
  for (ImageSegment& segment : data.segments) {
    segment.start = {10, 10};
    segment.end = {100, 10};
  }
  data.predicted_T_world_camera.pose = makePose(position, Eigen::Quaterniond::Identity());
  return std::make_unique<LineSetMessage>(data);
}

TEST(LineSetHandler, AnswersWithThePredictedPoseAndTheModelLinesNearIt) {
  test::TestDatabase database("handler");
  test::insertCubeBuilding(database.conninfo(), 85000, 447000, 0, 0);
  ModelMap map(database.conninfo(), "test");
  LineSetHandler handler(map, MessageLimits{}, 50.0);

  const std::optional<PoseFixData> fix = handler.handle(validMessage({5, -20, 1.5})->message());
  ASSERT_TRUE(fix.has_value());
  EXPECT_EQ(fix->robot_id, "handler-test");
  EXPECT_EQ(fix->sequence_number, 3u);
  EXPECT_EQ(fix->stamp_ns, 1'000'000);
  EXPECT_EQ(fix->status, lineloc_msg_FIX_NO_MATCH_COMPUTED);
  EXPECT_EQ(fix->model_lines, 12u);
  EXPECT_TRUE(fix->T_world_camera.pose.translation().isApprox(Eigen::Vector3d(5, -20, 1.5)));
  EXPECT_GT(fix->timings.total, 0);

  EXPECT_EQ(handler.handle(validMessage({5000, 0, 1.5})->message())->status,
            lineloc_msg_FIX_NO_MAP_LINES);
  EXPECT_EQ(handler.counters().answered, 2u);
}

TEST(LineSetHandler, DropsAndCountsMalformedInputThenKeepsServing) {
  test::TestDatabase database("handler_bad");
  test::insertCubeBuilding(database.conninfo(), 85000, 447000, 0, 0);
  ModelMap map(database.conninfo(), "test");
  MessageLimits limits;
  limits.max_segments = 3;
  LineSetHandler handler(map, limits, 50.0);

  const auto holder = validMessage({5, -20, 1.5});
  lineloc_msg_LineSet oversized = holder->message();
  EXPECT_FALSE(handler.handle(oversized).has_value());
  oversized.segments._length = 2;
  oversized.segments._buffer[1].end[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(handler.handle(oversized).has_value());
  EXPECT_NE(handler.counters().last_drop_reason.find("segments[1].end"), std::string::npos);
  oversized.segments._buffer[1].end[0] = 5.0f;
  EXPECT_TRUE(handler.handle(oversized).has_value());
  EXPECT_EQ(handler.counters().received, 3u);
  EXPECT_EQ(handler.counters().dropped_invalid, 2u);
  EXPECT_EQ(handler.counters().answered, 1u);
}

TEST(LineSetHandler, UnreachableDatabaseIsAnsweredAsInternalErrorAndCounted) {
  ModelMap map("host=127.0.0.1 port=1 user=nobody dbname=none connect_timeout=2", "test");
  LineSetHandler handler(map, MessageLimits{}, 50.0);
  const auto fix = handler.handle(validMessage({0, 0, 0})->message());
  ASSERT_TRUE(fix.has_value());
  EXPECT_EQ(fix->status, lineloc_msg_FIX_INTERNAL_ERROR);
  EXPECT_EQ(handler.counters().map_errors, 1u);
}

}  // namespace
}  // namespace lineloc
