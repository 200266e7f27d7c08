// The backbone's per-message pipeline against a real PostGIS database:
// validation, map tiles, hidden-line removal, model alignment.
#include <gtest/gtest.h>

#include <limits>
#include <map>
#include <memory>
#include <random>

#include "backbone/map/database_tile_fetcher.h"
#include "backbone/matching/line_matcher.h"
#include "backbone/service/line_set_handler.h"
#include "backbone/service/map_geometry.h"
#include "common/time/clock.h"
#include "common/time/utc_time.h"
#include "db/enrichment_store.h"
#include "tests/support/test_database.h"

namespace lineloc {
namespace {

const PinholeCamera kCamera{500, 500, 320, 240, 0, 640, 480};
// Grey-level step across each observed edge: a building edge in daylight,
// which searches take (AcquisitionOptions::min_segment_contrast).
constexpr float kEdgeContrast = 40.0f;

// Camera looking north; by default with a covariance too wide to track from.
PoseWithCovariance lookingNorth(const Eigen::Vector3d& position, double position_sigma_m = 0.3,
                                double rotation_sigma_rad = 0.02) {
  Eigen::Matrix3d R_world_camera;
  R_world_camera << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  PoseWithCovariance pose;
  pose.pose.linear() = R_world_camera;
  pose.pose.translation() = position;
  pose.covariance = diagonalPoseCovariance(position_sigma_m, rotation_sigma_rad);
  return pose;
}

std::unique_ptr<LineSetMessage> lineSetMessage(std::vector<ImageSegment> segments,
                                               const PoseWithCovariance& predicted,
                                               uint32_t sequence_number = 3,
                                               const std::string& robot_id = "handler-test") {
  LineSetData data;
  data.robot_id = robot_id;
  data.sequence_number = sequence_number;
  data.stamp_ns = 1'000'000 + sequence_number * 50'000'000LL;
  data.camera = kCamera;
  data.segments = std::move(segments);
  data.predicted_T_world_camera = predicted;
  return std::make_unique<LineSetMessage>(data);
}

std::vector<ImageSegment> fewSegments() {
  std::vector<ImageSegment> segments(4);
  for (ImageSegment& segment : segments) {
    segment.start = {10, 10};
    segment.end = {100, 10};
  }
  return segments;
}

// The handler prepares the map around a frame off the frame's path
// (prepared_maps.h): another robot's frame at `position` is answered without
// a pose while it does. Returns once the map there is prepared.
void prepareMapAt(LineSetHandler& handler, const Eigen::Vector3d& position) {
  const auto first = handler.handle(
      lineSetMessage(fewSegments(), lookingNorth(position, 0.1, 0.003), 1, "map-warm-up")
          ->message());
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->status, lineloc_msg_FIX_NO_MATCH_COMPUTED) << toString(first->status);
  EXPECT_EQ(first->model_lines, 0u);
  handler.waitForSearches();
}

class LineSetHandlerTest : public ::testing::Test {
 protected:
  LineSetHandlerTest() {
    test::insertCubeBuilding(database_.conninfo(), 85000, 447000, 0, 0);
    test::insertCubeBuilding(database_.conninfo(), 85000, 447000, 16, 4);
  }

  MapTileCache makeCache(const std::string& conninfo) {
    return MapTileCache([conninfo] { return makeDatabaseTileFetcher(conninfo, "test"); }, 100.0,
                        64);
  }

  test::TestDatabase database_{"handler"};
};

// What the camera at `truth` sees of the two cubes, with 0.3 px noise.
std::vector<ImageSegment> observedEdges(const std::string& conninfo,
                                        const PoseWithCovariance& truth) {
  db::Connection connection(conninfo);
  db::MapTileQuery query(connection, *db::findSite(connection, "test"));
  const db::TileContents tile =
      query.within({Eigen::Vector2d(-100, -100), Eigen::Vector2d(100, 100)});
  const OcclusionScene scene = occlusionScene(tile.faces);
  const std::vector<ModelSegment> lines = modelSegments(tile.lines);
  std::mt19937 random(1);
  std::normal_distribution<double> noise(0.0, 0.3);
  std::vector<ImageSegment> segments;
  for (const VisibleSegment& seen : visibleSegments(lines, scene, truth, kCamera, {})) {
    const ProjectedSegment p = projectSegment(seen.start_world, seen.end_world, truth, kCamera);
    ImageSegment segment;
    segment.start = (p.start_px + Eigen::Vector2d(noise(random), noise(random))).cast<float>();
    segment.end = (p.end_px + Eigen::Vector2d(noise(random), noise(random))).cast<float>();
    segment.start_covariance = Eigen::Matrix2f::Identity() * 0.09f;
    segment.end_covariance = segment.start_covariance;
    segment.contrast = kEdgeContrast;
    segments.push_back(segment);
  }
  return segments;
}

void expectWithinThreeSigma(const PoseWithCovariance& fix, const PoseWithCovariance& truth) {
  const Eigen::Vector3d error = fix.pose.translation() - truth.pose.translation();
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_LT(std::abs(error[axis]), 3.0 * std::sqrt(fix.covariance(axis, axis)))
        << "axis " << axis;
  }
}

TEST_F(LineSetHandlerTest, TracksFromAGoodPrediction) {
  MapTileCache cache = makeCache(database_.conninfo());
  LineSetHandler handler(cache, MessageLimits{}, PipelineOptions{});
  prepareMapAt(handler, {13, -30, 1.5});
  const PoseWithCovariance truth = lookingNorth({13, -30, 1.5});
  PoseWithCovariance predicted = lookingNorth({13.05, -30.04, 1.5}, 0.1, 0.003);
  const auto fix = handler.handle(
      lineSetMessage(observedEdges(database_.conninfo(), truth), predicted)->message());
  ASSERT_TRUE(fix.has_value());
  EXPECT_EQ(fix->robot_id, "handler-test");
  EXPECT_EQ(fix->sequence_number, 3u);
  EXPECT_EQ(fix->stamp_ns, 151'000'000);
  ASSERT_EQ(fix->status, lineloc_msg_FIX_OK) << toString(fix->status);
  EXPECT_EQ(fix->model_lines, 24u);
  expectWithinThreeSigma(fix->T_world_camera, truth);
  EXPECT_GT(fix->timings.total, 0);
  EXPECT_GE(fix->timings.total, fix->timings.map);
  EXPECT_EQ(handler.counters().fixes_ok, 1u);
  EXPECT_EQ(handler.counters().searches, 0u);
}

// A frame whose exposure notice came first is answered as it would be
// without one: the hidden lines removed at its exposure are those tracking
// removes from its prediction.
TEST_F(LineSetHandlerTest, TracksWithTheHiddenLinesRemovedAtExposure) {
  MapTileCache cache = makeCache(database_.conninfo());
  LineSetHandler noticed(cache, MessageLimits{}, PipelineOptions{});
  LineSetHandler unnoticed(cache, MessageLimits{}, PipelineOptions{});
  prepareMapAt(noticed, {13, -30, 1.5});
  prepareMapAt(unnoticed, {13, -30, 1.5});
  const PoseWithCovariance truth = lookingNorth({13, -30, 1.5});
  const PoseWithCovariance predicted = lookingNorth({13.05, -30.04, 1.5}, 0.1, 0.003);
  noticed.handleExposure(lineSetMessage({}, predicted)->message());
  const auto line_set = lineSetMessage(observedEdges(database_.conninfo(), truth), predicted);
  const auto fix = noticed.handle(line_set->message());
  const auto reference = unnoticed.handle(line_set->message());
  ASSERT_TRUE(fix.has_value() && reference.has_value());
  ASSERT_EQ(fix->status, lineloc_msg_FIX_OK) << toString(fix->status);
  EXPECT_EQ(noticed.counters().visibility_ahead, 1u);
  EXPECT_EQ(unnoticed.counters().visibility_ahead, 0u);
  EXPECT_EQ(fix->status, reference->status);
  EXPECT_EQ(fix->inliers, reference->inliers);
  EXPECT_EQ(fix->T_world_camera.pose.matrix(), reference->T_world_camera.pose.matrix());
  EXPECT_EQ(fix->T_world_camera.covariance, reference->T_world_camera.covariance);
  expectWithinThreeSigma(fix->T_world_camera, truth);
}

// The steady clock a handler with `options` forgets the robots it heard
// from until now at.
int64_t onceSilentFor(const PipelineOptions& options) {
  return steadyClockNs() + static_cast<int64_t>(options.forget_robot_after_s * 1e9) + 1;
}

// The map around the camera north of the cubes prepared: what the camera
// there sees, and a prediction 6 cm off to track it from.
std::pair<std::vector<ImageSegment>, PoseWithCovariance> trackableView(
    LineSetHandler& handler, const std::string& conninfo) {
  prepareMapAt(handler, {13, -30, 1.5});
  return {observedEdges(conninfo, lookingNorth({13, -30, 1.5})),
          lookingNorth({13.05, -30.04, 1.5}, 0.1, 0.003)};
}

// With learning on, the frames answered OK teach the map the edges painted
// on a cube's face that no model line explains, written once the robot is
// forgotten, on the cube's building. The robot is tracked from its own
// prediction, so its fixes stay widened until the proof search the first
// frame starts agrees (to 0.16 m in position): the test waits for it and
// takes segments placed that well.
TEST_F(LineSetHandlerTest, LearnsTheLinesOfTheFramesItAnswersOk) {
  // The first cube's south face (y = 0), which the sill is painted on.
  db::Connection owner(database_.conninfo());
  owner.execParams(
      "INSERT INTO face (site_id, building_id, kind, geom) SELECT site_id, id, 1, "
      "ST_GeomFromText('POLYGON Z ((85000 447000 0, 85010 447000 0, 85010 447000 10, 85000 "
      "447000 10, 85000 447000 0))', 7415) FROM building WHERE source_id = 'cube-0-0'",
      {});
  MapTileCache cache = makeCache(database_.conninfo());
  PipelineOptions options;
  options.learning.db = database_.conninfo(test::DatabaseRole::kEnricher);
  options.learning.site = "test";
  options.learning.frame_interval_s = 0.0;
  options.learning.learner.observation.max_placement_sigma_m = 0.5;
  {
    LineSetHandler handler(cache, MessageLimits{}, options);
    prepareMapAt(handler, {12, -20, 1.5});
    // A window's sill on the first cube's south face (y = 0), 3 m up.
    const Eigen::Vector3d sill_start(2.0, 0.0, 3.0);
    const Eigen::Vector3d sill_end(6.0, 0.0, 3.0);
    for (int k = 0; k < 9; ++k) {
      const Eigen::Vector3d position(10.0 + 0.5 * k, -20.0, 1.5);
      const PoseWithCovariance truth = lookingNorth(position);
      std::vector<ImageSegment> seen = observedEdges(database_.conninfo(), truth);
      const ProjectedSegment sill = projectSegment(sill_start, sill_end, truth, kCamera);
      ImageSegment painted = seen.front();
      painted.start = sill.start_px.cast<float>();
      painted.end = sill.end_px.cast<float>();
      seen.push_back(painted);
      const PoseWithCovariance predicted =
          lookingNorth(position + Eigen::Vector3d(0.05, -0.04, 0.0), 0.1, 0.003);
      ASSERT_EQ(handler.handle(lineSetMessage(seen, predicted, 3 + k)->message())->status,
                lineloc_msg_FIX_OK);
      handler.waitForSearches();
    }
    handler.forgetSilentRobots(onceSilentFor(options));
    handler.waitForLearning();
  }
  db::Connection reader(database_.conninfo(test::DatabaseRole::kReader));
  const std::vector<db::StoredEnrichmentLine> lines =
      db::readEnrichment(reader, db::requireSite(reader, "test"));
  ASSERT_EQ(lines.size(), 1u);
  // On the face where the occlusion scene's ray cast met it, in single
  // precision: within a few micrometres at 20 m.
  EXPECT_NEAR(lines[0].start_world.y(), 0.0, 1e-4);
  EXPECT_NEAR(lines[0].start_world.z(), 3.0, 0.05);
  EXPECT_NEAR(lines[0].end_world.z(), 3.0, 0.05);
  const std::string cube_id =
      reader.execParams("SELECT id FROM building WHERE source_id = 'cube-0-0'", {}).text(0, 0);
  EXPECT_EQ(lines[0].building_id, std::stoll(cube_id));
}

// A notice for another frame, one whose prediction the LineSet does not
// carry, or one its robot left before it was forgotten (the notice held a
// prepared map), is not taken: the frame's hidden lines are removed again.
TEST_F(LineSetHandlerTest, TakesNoHiddenLinesRemovedForAnotherFrameOrPredictionOrForgottenRobot) {
  MapTileCache cache = makeCache(database_.conninfo());
  LineSetHandler handler(cache, MessageLimits{}, PipelineOptions{});
  const auto [seen, predicted] = trackableView(handler, database_.conninfo());
  handler.handleExposure(lineSetMessage({}, predicted, 3)->message());
  EXPECT_EQ(handler.handle(lineSetMessage(seen, predicted, 4)->message())->status,
            lineloc_msg_FIX_OK);
  handler.handleExposure(
      lineSetMessage({}, lookingNorth({13.1, -30, 1.5}, 0.1, 0.003), 5)->message());
  EXPECT_EQ(handler.handle(lineSetMessage(seen, predicted, 5)->message())->status,
            lineloc_msg_FIX_OK);
  handler.handleExposure(lineSetMessage({}, predicted, 6)->message());
  handler.forgetSilentRobots(onceSilentFor(PipelineOptions{}));
  EXPECT_EQ(handler.handle(lineSetMessage(seen, predicted, 6)->message())->status,
            lineloc_msg_FIX_OK);
  EXPECT_EQ(handler.counters().visibility_ahead, 0u);
  EXPECT_EQ(handler.counters().fixes_ok, 3u);
}

// A notice that comes after its LineSet, or after a later one (its thread
// held up on a loaded machine), is skipped and counted; the next frame's, on
// time, is taken.
TEST_F(LineSetHandlerTest, SkipsANoticeThatComesAfterItsLineSet) {
  MapTileCache cache = makeCache(database_.conninfo());
  LineSetHandler handler(cache, MessageLimits{}, PipelineOptions{});
  const auto [seen, predicted] = trackableView(handler, database_.conninfo());
  EXPECT_EQ(handler.handle(lineSetMessage(seen, predicted, 3)->message())->status,
            lineloc_msg_FIX_OK);
  handler.handleExposure(lineSetMessage({}, predicted, 3)->message());
  handler.handleExposure(lineSetMessage({}, predicted, 2)->message());
  EXPECT_EQ(handler.counters().notices_after_line_set, 2u);

  handler.handleExposure(lineSetMessage({}, predicted, 4)->message());
  EXPECT_EQ(handler.handle(lineSetMessage(seen, predicted, 4)->message())->status,
            lineloc_msg_FIX_OK);
  EXPECT_EQ(handler.counters().visibility_ahead, 1u);
  EXPECT_EQ(handler.counters().notices_after_line_set, 2u);
}

// A LineSets' thread a frame behind its robot's notices takes its frame's
// notice and leaves the next frame's to that frame; a notice whose LineSet
// never came is dropped by the next LineSet, not taken by it.
TEST_F(LineSetHandlerTest, KeepsTheNoticesOfFramesStillToCome) {
  MapTileCache cache = makeCache(database_.conninfo());
  LineSetHandler handler(cache, MessageLimits{}, PipelineOptions{});
  const auto [seen, predicted] = trackableView(handler, database_.conninfo());
  handler.handleExposure(lineSetMessage({}, predicted, 3)->message());
  handler.handleExposure(lineSetMessage({}, predicted, 4)->message());
  handler.handleExposure(lineSetMessage({}, predicted, 5)->message());
  EXPECT_EQ(handler.handle(lineSetMessage(seen, predicted, 4)->message())->status,
            lineloc_msg_FIX_OK);
  EXPECT_EQ(handler.handle(lineSetMessage(seen, predicted, 5)->message())->status,
            lineloc_msg_FIX_OK);
  EXPECT_EQ(handler.counters().visibility_ahead, 2u);
  EXPECT_EQ(handler.handle(lineSetMessage(seen, predicted, 3)->message())->status,
            lineloc_msg_FIX_OK);
  EXPECT_EQ(handler.counters().visibility_ahead, 2u);
  EXPECT_EQ(handler.counters().notices_after_line_set, 0u);
}

// A malformed notice is dropped and counted; the frame is answered all the same.
TEST_F(LineSetHandlerTest, DropsAndCountsAMalformedExposureNotice) {
  MapTileCache cache = makeCache(database_.conninfo());
  LineSetHandler handler(cache, MessageLimits{}, PipelineOptions{});
  prepareMapAt(handler, {13, -30, 1.5});
  const PoseWithCovariance predicted = lookingNorth({13.05, -30.04, 1.5}, 0.1, 0.003);
  const auto holder = lineSetMessage({}, predicted);
  lineloc_msg_LineSet notice = holder->message();
  notice.predicted_T_world_camera.pose.rotation_xyzw[3] = 7.0;
  handler.handleExposure(notice);
  EXPECT_EQ(handler.counters().dropped_invalid, 1u);
  EXPECT_NE(handler.counters().last_drop_reason.find("predicted_T_world_camera"), std::string::npos)
      << handler.counters().last_drop_reason;
  const auto fix = handler.handle(
      lineSetMessage(observedEdges(database_.conninfo(), lookingNorth({13, -30, 1.5})), predicted)
          ->message());
  ASSERT_TRUE(fix.has_value());
  EXPECT_EQ(fix->status, lineloc_msg_FIX_OK) << toString(fix->status);
  EXPECT_EQ(handler.counters().visibility_ahead, 0u);
  EXPECT_EQ(handler.counters().received, 2u);
}

// No frame waits for the database or for a scene to be built: the first one
// is answered without a pose while its map is prepared, a frame 40 m on, whose
// own view is not prepared yet, is localized in the one prepared nearby.
TEST_F(LineSetHandlerTest, AnswersAtOnceWhileTheMapIsPreparedThenTracks) {
  MapTileCache cache = makeCache(database_.conninfo());
  LineSetHandler handler(cache, MessageLimits{}, PipelineOptions{});
  const PoseWithCovariance truth = lookingNorth({13, -30, 1.5});
  const auto message = lineSetMessage(observedEdges(database_.conninfo(), truth),
                                      lookingNorth({13.05, -30.04, 1.5}, 0.1, 0.003));
  const auto first = handler.handle(message->message());
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->status, lineloc_msg_FIX_NO_MATCH_COMPUTED) << toString(first->status);
  handler.waitForSearches();
  const auto tracked = handler.handle(message->message());
  ASSERT_TRUE(tracked.has_value());
  EXPECT_EQ(tracked->status, lineloc_msg_FIX_OK) << toString(tracked->status);
  EXPECT_EQ(tracked->model_lines, 24u);

  // 40 m east the query square takes another column of tiles.
  const auto moved = handler.handle(
      lineSetMessage(fewSegments(), lookingNorth({53, -30, 1.5}, 0.1, 0.003), 4)->message());
  ASSERT_TRUE(moved.has_value());
  EXPECT_EQ(moved->status, lineloc_msg_FIX_TOO_FEW_MATCHES) << toString(moved->status);
  EXPECT_EQ(moved->model_lines, 24u);
  EXPECT_EQ(handler.counters().searches, 0u);
}

TEST(SunlightAt, IsTheClocksSunOverTheSiteWhenAskedForElseTheGivenOne) {
  PipelineOptions options;
  const int64_t morning_ns = parseUtcTime_ns("2026-04-14T09:30:00Z");
  EXPECT_FALSE(sunlightAt(options, morning_ns).has_value());
  options.localizer.visibility.sunlight = Sunlight::fromAzimuthElevation(135.0, 40.0, 0.35);
  EXPECT_EQ(sunlightAt(options, morning_ns)->direction_world,
            options.localizer.visibility.sunlight->direction_world);
  const SiteSun delft(SiteProjection("EPSG:7415", {84900, 447600, 0}), 0.35);
  options.sun_from_clock = delft;
  // The clock's sun replaces the given one, each LineSet under its own time's.
  const std::optional<Sunlight> morning = sunlightAt(options, morning_ns);
  ASSERT_TRUE(morning.has_value());
  EXPECT_EQ(morning->direction_world, delft.at(morning_ns)->direction_world);
  const int64_t later_ns = morning_ns + 3'600'000'000'000;
  EXPECT_EQ(sunlightAt(options, later_ns)->direction_world, delft.at(later_ns)->direction_world);
  EXPECT_GT((morning->direction_world - sunlightAt(options, later_ns)->direction_world).norm(),
            0.1);
  // At night no sun, not the given one.
  EXPECT_FALSE(sunlightAt(options, parseUtcTime_ns("2026-04-14T22:00:00Z")).has_value());
}

// A robot 0.3 m off (too far to track) whose frames 2, 3 see the view from
// `truth`, and whose frame 4 sees it 1 m further north, where its own
// prediction moved too.
struct PoorStart {
  PoseWithCovariance truth = lookingNorth({13, -30, 1.5});
  PoseWithCovariance predicted = lookingNorth({13.25, -30.2, 1.55});
  PoseWithCovariance truth_moved = lookingNorth({13, -29, 1.5});
  PoseWithCovariance predicted_moved = lookingNorth({13.25, -29.2, 1.55});
};

// A frame the handler must search from: answered at once, without a pose;
// returns once its search has finished.
void expectSearched(LineSetHandler& handler, const std::vector<ImageSegment>& seen,
                    const PoseWithCovariance& predicted, uint32_t sequence) {
  const auto answer = handler.handle(lineSetMessage(seen, predicted, sequence)->message());
  ASSERT_TRUE(answer.has_value());
  EXPECT_EQ(answer->status, lineloc_msg_FIX_NO_MATCH_COMPUTED) << toString(answer->status);
  handler.waitForSearches();
}

// Frame 4, after frames 2 and 3 were searched: the camera at `truth`, tracked
// from the pose its searches took, moved by the robot's motion, without a search.
void expectTrackedAfterSearches(LineSetHandler& handler, const std::string& conninfo,
                                const PoseWithCovariance& truth,
                                const PoseWithCovariance& predicted) {
  const auto fix =
      handler.handle(lineSetMessage(observedEdges(conninfo, truth), predicted, 4)->message());
  ASSERT_TRUE(fix.has_value());
  ASSERT_EQ(fix->status, lineloc_msg_FIX_OK) << toString(fix->status);
  expectWithinThreeSigma(fix->T_world_camera, truth);
  EXPECT_LT((fix->T_world_camera.pose.translation() - truth.pose.translation()).norm(), 0.1);
  EXPECT_EQ(handler.counters().searches, 2u);
}

// The map prepared and `start`'s frames 2 and 3 searched for, the second
// taking the pose both found; returns what the camera sees there.
std::vector<ImageSegment> takePoorStart(LineSetHandler& handler, const std::string& conninfo,
                                        const PoorStart& start) {
  prepareMapAt(handler, {13, -30, 1.5});
  const std::vector<ImageSegment> seen = observedEdges(conninfo, start.truth);
  expectSearched(handler, seen, start.predicted, 2);
  expectSearched(handler, seen, start.predicted, 3);
  return seen;
}

TEST_F(LineSetHandlerTest, SearchesFromAPoorPredictionThenTracksFromTheConfirmedPose) {
  MapTileCache cache = makeCache(database_.conninfo());
  LineSetHandler handler(cache, MessageLimits{}, PipelineOptions{});
  prepareMapAt(handler, {13, -30, 1.5});
  const PoorStart start;
  const std::vector<ImageSegment> seen = observedEdges(database_.conninfo(), start.truth);
  ASSERT_GE(seen.size(), 6u);

  // One frame is no evidence: the pose found waits for the second.
  expectSearched(handler, seen, start.predicted, 2);
  expectSearched(handler, seen, start.predicted, 3);
  EXPECT_EQ(handler.counters().searches, 2u);
  EXPECT_EQ(handler.counters().fixes_ok, 0u);

  expectTrackedAfterSearches(handler, database_.conninfo(), start.truth_moved,
                             start.predicted_moved);
  EXPECT_EQ(handler.counters().fixes_ok, 1u);
}

TEST_F(LineSetHandlerTest, ASearchIsCarriedAcrossACorrectionOfTheRobotsPrediction) {
  MapTileCache cache = makeCache(database_.conninfo());
  LineSetHandler handler(cache, MessageLimits{}, PipelineOptions{});
  const PoorStart start;
  takePoorStart(handler, database_.conninfo(), start);
  // The robot stood still; a DGPS update moved its prediction 2 m north and
  // shrank its covariance (still too wide to track from).
  PoseWithCovariance corrected = start.predicted;
  corrected.pose.translation() += Eigen::Vector3d(0.0, 2.0, 0.0);
  corrected.covariance = diagonalPoseCovariance(0.25, 0.02);
  expectTrackedAfterSearches(handler, database_.conninfo(), start.truth, corrected);
}

// Frames `first_sequence` on of a robot at `truth`, its prediction moving
// alike, tracked from there without a search: widened by the proof search's
// prior until the first one, which its first frame runs from the tracking
// start's own viewpoint, has looked around, then by the search's resolution,
// stating each as their unproven part, until, once the robot has moved
// acquisition_proven_after_m, a proof search from there agrees with
// tracking, and a second one proof_retry_m further on does too. The first
// proves nothing by agreeing.
void expectProvenBySearchesFromElsewhere(LineSetHandler& handler, const std::string& conninfo,
                                         const PipelineOptions& options, PoseWithCovariance truth,
                                         PoseWithCovariance predicted, uint32_t first_sequence) {
  const AcquisitionOptions& acquisition = options.localizer.acquisition;
  const double acquired_variance = std::pow(acquisition.acquired_position_sigma_m, 2);
  uint32_t sequence = first_sequence;
  const auto expectFix = [&](double unproven_position_sigma_m, double unproven_rotation_sigma_rad) {
    const auto fix = handler.handle(
        lineSetMessage(observedEdges(conninfo, truth), predicted, sequence)->message());
    ASSERT_TRUE(fix.has_value());
    ASSERT_EQ(fix->status, lineloc_msg_FIX_OK) << toString(fix->status);
    expectWithinThreeSigma(fix->T_world_camera, truth);
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_EQ(fix->T_world_camera.covariance(axis, axis) >= acquired_variance,
                unproven_position_sigma_m > 0.0)
          << "frame " << sequence << ", axis " << axis;
    }
    EXPECT_EQ(fix->unproven_position_sigma_m, unproven_position_sigma_m) << "frame " << sequence;
    EXPECT_EQ(fix->unproven_rotation_sigma_rad, unproven_rotation_sigma_rad)
        << "frame " << sequence;
    ++sequence;
  };
  const auto expectUnlookedFix = [&] {
    expectFix(options.robot.proof.proof_position_sigma_m, options.robot.proof.confirm_rotation_rad);
  };
  const auto expectUnprovenFix = [&] {
    expectFix(acquisition.acquired_position_sigma_m, acquisition.acquired_rotation_sigma_rad);
  };
  const auto driveNorth = [&](double distance_m) {
    truth.pose.translation().y() += distance_m;
    predicted.pose.translation().y() += distance_m;
  };
  const uint64_t searches = handler.counters().searches;

  expectUnlookedFix();
  handler.waitForSearches();
  EXPECT_EQ(handler.counters().searches, searches + 1);
  expectUnprovenFix();
  EXPECT_EQ(handler.counters().searches, searches + 1);
  // 1.5 m further north: the first proof search from elsewhere is due;
  // agreeing, it leaves the fixes widened.
  driveNorth(1.5);
  expectUnprovenFix();
  handler.waitForSearches();
  EXPECT_EQ(handler.counters().searches, searches + 2);
  expectUnprovenFix();
  EXPECT_EQ(handler.counters().searches, searches + 2);
  // A metre further on, the second one is due; agreeing too, it proves tracking.
  driveNorth(options.robot.proof.proof_retry_m);
  expectUnprovenFix();
  handler.waitForSearches();
  EXPECT_EQ(handler.counters().searches, searches + 3);
  expectFix(0.0, 0.0);
  EXPECT_EQ(handler.counters().searches, searches + 3);
}

// A robot that stands still searches the same view twice, and both searches
// can settle in the same wrong basin: its fixes stay unproven until searches
// from elsewhere agree.
TEST_F(LineSetHandlerTest, FixesKeepTheSearchsResolutionUntilSearchesFromElsewhereAgree) {
  MapTileCache cache = makeCache(database_.conninfo());
  const PipelineOptions options;
  LineSetHandler handler(cache, MessageLimits{}, options);
  const PoorStart start;
  takePoorStart(handler, database_.conninfo(), start);
  expectProvenBySearchesFromElsewhere(handler, database_.conninfo(), options, start.truth,
                                      start.predicted, 4);
}

// A robot that this backbone tracks from its own prediction (as after a
// restart of the backbone) stands on fixes whose proof the backbone never
// saw: its fixes are proven as those of a searched robot are, and again once
// its odometry starts anew.
TEST_F(LineSetHandlerTest, ARobotTrackedFromItsOwnPredictionIsProvenLikeASearchedOne) {
  MapTileCache cache = makeCache(database_.conninfo());
  const PipelineOptions options;
  LineSetHandler handler(cache, MessageLimits{}, options);
  prepareMapAt(handler, {13, -30, 1.5});
  expectProvenBySearchesFromElsewhere(handler, database_.conninfo(), options,
                                      lookingNorth({13, -30, 1.5}),
                                      lookingNorth({13.05, -30.04, 1.5}, 0.1, 0.003), 3);
  EXPECT_EQ(handler.counters().searches, 3u);

  // A frame older than the last (the robot restarted): its odometry starts a
  // new chain, and its motion since the tracking start is unknown.
  const PoseWithCovariance truth = lookingNorth({13, -27.5, 1.5});
  const auto fix = handler.handle(lineSetMessage(observedEdges(database_.conninfo(), truth),
                                                 lookingNorth({13.05, -27.54, 1.5}, 0.1, 0.003), 2)
                                      ->message());
  ASSERT_TRUE(fix.has_value());
  ASSERT_EQ(fix->status, lineloc_msg_FIX_OK) << toString(fix->status);
  expectWithinThreeSigma(fix->T_world_camera, truth);
  EXPECT_EQ(fix->unproven_position_sigma_m, options.robot.proof.proof_position_sigma_m);
}

// Two backbones share a robot through their handovers (a map stands in for
// their topic, tracking_handovers.h). Proven on the first, then left to the
// second, the robot is tracked there proven from its first frame, with no
// proof search; taken back by the first, which forgot it when it left it, it
// is tracked there proven from the second's handover.
TEST_F(LineSetHandlerTest, ARobotTakenOverContinuesTheProofItsLastBackboneHandedOver) {
  std::map<std::string, TrackingHandover> topic;
  const HandoverChannel channel{
      [&](const std::string& robot_id, const TrackingHandover& handover) {
        topic[robot_id] = handover;
      },
      [&](const std::string& robot_id) -> std::optional<TrackingHandover> {
        const auto found = topic.find(robot_id);
        return found != topic.end() ? std::optional(found->second) : std::nullopt;
      }};
  const PipelineOptions options;
  MapTileCache first_cache = makeCache(database_.conninfo());
  LineSetHandler first(first_cache, MessageLimits{}, options, channel);
  prepareMapAt(first, {13, -30, 1.5});
  expectProvenBySearchesFromElsewhere(first, database_.conninfo(), options,
                                      lookingNorth({13, -30, 1.5}),
                                      lookingNorth({13.05, -30.04, 1.5}, 0.1, 0.003), 3);
  ASSERT_TRUE(topic.contains("handler-test"));
  EXPECT_TRUE(topic["handler-test"].tracking);
  EXPECT_EQ(topic["handler-test"].agreeing_proofs, options.robot.proof.agreeing_proofs_needed);
  const uint64_t first_searches = first.counters().searches;
  first.leaveToAnotherBackbone("handler-test");
  EXPECT_EQ(first.counters().frames_served_elsewhere, 1u);
  EXPECT_EQ(first.counters().robots, 1u) << "the warm-up robot alone";

  // A tracked robot's prediction: 2 cm off, 2 cm and 0.05 degree wide.
  const auto expectProvenFix = [&](LineSetHandler& handler, uint32_t sequence, double north_m) {
    const PoseWithCovariance truth = lookingNorth({13, north_m, 1.5});
    const PoseWithCovariance predicted = lookingNorth({13.02, north_m + 0.01, 1.5}, 0.02, 0.001);
    const auto fix = handler.handle(
        lineSetMessage(observedEdges(database_.conninfo(), truth), predicted, sequence)->message());
    ASSERT_TRUE(fix.has_value());
    ASSERT_EQ(fix->status, lineloc_msg_FIX_OK) << toString(fix->status);
    expectWithinThreeSigma(fix->T_world_camera, truth);
    EXPECT_EQ(fix->unproven_position_sigma_m, 0.0) << "frame " << sequence;
    EXPECT_EQ(fix->unproven_rotation_sigma_rad, 0.0) << "frame " << sequence;
    handler.waitForSearches();
  };
  MapTileCache second_cache = makeCache(database_.conninfo());
  LineSetHandler second(second_cache, MessageLimits{}, options, channel);
  prepareMapAt(second, {13, -27.5, 1.5});
  expectProvenFix(second, 20, -27.5);
  expectProvenFix(second, 21, -27.4);
  EXPECT_EQ(second.counters().searches, 0u);

  second.leaveToAnotherBackbone("handler-test");
  expectProvenFix(first, 22, -27.3);
  EXPECT_EQ(first.counters().searches, first_searches);
}

// A proof search judges the tracking start it was submitted for. A robot
// restarted while its first proof search waits starts tracking anew: that
// proof, returning after the restart, neither ends the new start's widening
// by the proof search's prior nor takes the place of the new start's own
// first proof. The searches step aside from a second before the robot's next
// frame is due, which its first frame puts 0.95 s after it (its stamp): the
// proof waits for the restarted robot's frame.
TEST_F(LineSetHandlerTest, AProofThatReturnsAfterTheRobotRestartedIsDropped) {
  MapTileCache cache = makeCache(database_.conninfo());
  PipelineOptions options;
  options.quiet_before_frame_ms = 1000.0;
  options.max_background_yield_ms = 1000.0;
  LineSetHandler handler(cache, MessageLimits{}, options);
  prepareMapAt(handler, {13, -30, 1.5});
  const PoseWithCovariance truth = lookingNorth({13, -30, 1.5});
  const PoseWithCovariance predicted = lookingNorth({13.05, -30.04, 1.5}, 0.1, 0.003);
  const std::vector<ImageSegment> seen = observedEdges(database_.conninfo(), truth);
  const auto expectFix = [&](uint32_t sequence, double unproven_position_sigma_m) {
    const auto fix = handler.handle(lineSetMessage(seen, predicted, sequence)->message());
    ASSERT_TRUE(fix.has_value());
    ASSERT_EQ(fix->status, lineloc_msg_FIX_OK) << toString(fix->status);
    EXPECT_EQ(fix->unproven_position_sigma_m, unproven_position_sigma_m) << "frame " << sequence;
  };
  // Frame 19 starts tracking and its proof search; frame 18, older, is the
  // restarted robot's first.
  expectFix(19, options.robot.proof.proof_position_sigma_m);
  expectFix(18, options.robot.proof.proof_position_sigma_m);
  handler.waitForSearches();
  EXPECT_EQ(handler.counters().searches, 1u);
  expectFix(19, options.robot.proof.proof_position_sigma_m);
  handler.waitForSearches();
  EXPECT_EQ(handler.counters().searches, 2u);
  expectFix(20, options.localizer.acquisition.acquired_position_sigma_m);
}

// Where the second view the camera sees lies, in tests that track beside the
// truth.
const Eigen::Vector3d kBeside(1.2, 0.0, 0.0);

// The same start, then the robot drives 1.5 m north, but its odometry says
// 1.2 m east too, and its image holds the view from the truth and, shortened
// to `beside_length` of its lines, the view from where the odometry puts it:
// tracking from the taken pose carried there settles on that view.
// Returns the frame of the proof search, once it has run.
struct TrackedBeside {
  PoseWithCovariance truth;
  PoseWithCovariance predicted;
  std::vector<ImageSegment> seen;
};

// A fix tracked beside `truth` whose covariance covers it, the offset stated
// as the fix's unproven part.
void expectCoversTheTruthAsItsUnprovenPart(const PoseFixData& fix,
                                           const PoseWithCovariance& truth) {
  const double offset_m = (fix.T_world_camera.pose.translation() - truth.pose.translation()).norm();
  EXPECT_GT(offset_m, 1.0);
  EXPECT_GE(fix.unproven_position_sigma_m, offset_m - 0.1);
  expectWithinThreeSigma(fix.T_world_camera, truth);
}

// The view from `truth` and, shortened to `beside_length` of its lines, the
// view from 1.2 m east of it.
std::vector<ImageSegment> seenWithTheViewBeside(const std::string& conninfo,
                                                const PoseWithCovariance& truth,
                                                float beside_length) {
  PoseWithCovariance beside = truth;
  beside.pose.translation() += kBeside;
  std::vector<ImageSegment> seen = observedEdges(conninfo, truth);
  for (ImageSegment segment : observedEdges(conninfo, beside)) {
    segment.end = segment.start + beside_length * (segment.end - segment.start);
    seen.push_back(segment);
  }
  return seen;
}

TrackedBeside trackBesideTheTruth(LineSetHandler& handler, const std::string& conninfo,
                                  float beside_length) {
  const PoorStart start;
  takePoorStart(handler, conninfo, start);
  TrackedBeside frame{start.truth, start.predicted, {}};
  frame.truth.pose.translation().y() += 1.5;
  const Eigen::Vector3d beside = frame.truth.pose.translation() + kBeside;
  frame.seen = seenWithTheViewBeside(conninfo, frame.truth, beside_length);
  frame.predicted.pose.translation() += kBeside + Eigen::Vector3d(0.0, 1.5, 0.0);
  const auto tracked = handler.handle(lineSetMessage(frame.seen, frame.predicted, 5)->message());
  EXPECT_TRUE(tracked.has_value());
  EXPECT_EQ(tracked->status, lineloc_msg_FIX_OK) << toString(tracked->status);
  EXPECT_LT((tracked->T_world_camera.pose.translation() - beside).norm(), 0.3);
  handler.waitForSearches();
  EXPECT_EQ(handler.counters().searches, 3u);
  return frame;
}

// With the view beside shortened to 0.4, the proof search over the metres
// around the tracked pose finds the truth, which the tracked pose scores far
// below. The robot's frames are then searched for again, not tracked, until
// the searches take a pose again, and tracking resumes from there.
TEST_F(LineSetHandlerTest, TrackingThatASearchFromElsewhereContradictsStops) {
  MapTileCache cache = makeCache(database_.conninfo());
  LineSetHandler handler(cache, MessageLimits{}, PipelineOptions{});
  const TrackedBeside frame = trackBesideTheTruth(handler, database_.conninfo(), 0.4f);

  expectSearched(handler, frame.seen, frame.predicted, 6);
  expectSearched(handler, frame.seen, frame.predicted, 7);
  const auto fix = handler.handle(lineSetMessage(frame.seen, frame.predicted, 8)->message());
  ASSERT_TRUE(fix.has_value());
  ASSERT_EQ(fix->status, lineloc_msg_FIX_OK) << toString(fix->status);
  EXPECT_LT((fix->T_world_camera.pose.translation() - frame.truth.pose.translation()).norm(), 0.1);
  EXPECT_EQ(handler.counters().searches, 5u);
}

// A robot tracked from its own narrow prediction beside the truth, whose
// proof search ends the tracking, stands still: its searches' pose is too
// wide to track from, which takes a second view, so its frames stay searched
// for, as its prediction stands on the disproven fixes. Found poses carry the
// searches' 0.15 m resolution (acquired_position_sigma_m), so with tracking
// limited to a 0.12 m sigma every one is too wide, and the 0.05 m prediction
// is not.
TEST_F(LineSetHandlerTest, AfterAContradictionOnlyASearchNarrowEnoughToTrackFromResumesTracking) {
  MapTileCache cache = makeCache(database_.conninfo());
  PipelineOptions options;
  options.localizer.max_tracking_position_sigma_m = 0.12;
  LineSetHandler handler(cache, MessageLimits{}, options);
  prepareMapAt(handler, {13, -30, 1.5});
  const PoseWithCovariance truth = lookingNorth({13, -28.5, 1.5});
  const PoseWithCovariance predicted =
      lookingNorth(truth.pose.translation() + kBeside, 0.05, 0.003);
  const std::vector<ImageSegment> seen = seenWithTheViewBeside(database_.conninfo(), truth, 0.4f);
  const auto tracked = handler.handle(lineSetMessage(seen, predicted, 3)->message());
  ASSERT_TRUE(tracked.has_value());
  ASSERT_EQ(tracked->status, lineloc_msg_FIX_OK) << toString(tracked->status);
  EXPECT_LT((tracked->T_world_camera.pose.translation() - predicted.pose.translation()).norm(),
            0.3);
  handler.waitForSearches();
  EXPECT_EQ(handler.counters().searches, 1u);

  expectSearched(handler, seen, predicted, 4);
  expectSearched(handler, seen, predicted, 5);
  expectSearched(handler, seen, predicted, 6);
  EXPECT_EQ(handler.counters().searches, 4u);
  EXPECT_EQ(handler.counters().fixes_ok, 1u);
}

// Tracked beside the truth with the view beside at 0.8 of its length, frame
// 6 is tracked on, its fix covering the truth, and no proof search is due.
void expectTrackedOnCoveringTheTruth(LineSetHandler& handler, const std::string& conninfo) {
  const TrackedBeside frame = trackBesideTheTruth(handler, conninfo, 0.8f);
  const auto fix = handler.handle(lineSetMessage(frame.seen, frame.predicted, 6)->message());
  ASSERT_TRUE(fix.has_value());
  ASSERT_EQ(fix->status, lineloc_msg_FIX_OK) << toString(fix->status);
  expectCoversTheTruthAsItsUnprovenPart(*fix, frame.truth);
  handler.waitForSearches();
  EXPECT_EQ(handler.counters().searches, 3u);
}

// With the view beside kept at 0.8 of its length, the tracked pose scores
// nearly as well as the truth the proof search finds: the image does not
// tell them apart, so tracking goes on, its fixes widened to cover the truth
// as their unproven part, and the proof is tried again after proof_retry_m
// more. The proof search aligns its best grid
// hypothesis only, so that it is the tracked pose's score, not a rival in the
// search, that leaves the proof undecided; and no edge counts as sky, where
// each view's roof corners lie seen from the other, so that coverage does.
TEST_F(LineSetHandlerTest, TrackingThatScoresNearlyAsWellAsTheProofSearchsPoseGoesOn) {
  MapTileCache cache = makeCache(database_.conninfo());
  PipelineOptions options;
  options.localizer.acquisition.search.max_hypotheses = 1;
  options.localizer.acquisition.sky_edges.min_elevation_rad = M_PI / 2;
  LineSetHandler handler(cache, MessageLimits{}, options);
  expectTrackedOnCoveringTheTruth(handler, database_.conninfo());
}

// The same view, the proof search aligning all its grid hypotheses: it
// finds both poses, too alike to choose between (kAmbiguous). Neither
// contradicts tracking, but the one elsewhere widens the fixes as above.
TEST_F(LineSetHandlerTest, AnAmbiguousProofSearchWidensTheFixesToCoverThePoseElsewhere) {
  MapTileCache cache = makeCache(database_.conninfo());
  PipelineOptions options;
  options.localizer.acquisition.sky_edges.min_elevation_rad = M_PI / 2;
  LineSetHandler handler(cache, MessageLimits{}, options);
  expectTrackedOnCoveringTheTruth(handler, database_.conninfo());
}

// Each robot's searches are its own: another robot at the same place, with
// the same poor prediction, is searched for, not carried by the first
// robot's taken pose.
TEST_F(LineSetHandlerTest, ARobotsConfirmedSearchCarriesNoOtherRobot) {
  MapTileCache cache = makeCache(database_.conninfo());
  LineSetHandler handler(cache, MessageLimits{}, PipelineOptions{});
  const PoorStart start;
  const std::vector<ImageSegment> seen = takePoorStart(handler, database_.conninfo(), start);
  const auto other = handler.handle(lineSetMessage(seen, start.predicted, 4, "other")->message());
  ASSERT_TRUE(other.has_value());
  EXPECT_EQ(other->status, lineloc_msg_FIX_NO_MATCH_COMPUTED) << toString(other->status);
  handler.waitForSearches();
  EXPECT_EQ(handler.counters().searches, 3u);
  const auto tracked =
      handler.handle(lineSetMessage(observedEdges(database_.conninfo(), start.truth_moved),
                                    start.predicted_moved, 4)
                         ->message());
  ASSERT_TRUE(tracked.has_value());
  EXPECT_EQ(tracked->status, lineloc_msg_FIX_OK) << toString(tracked->status);
}

// A robot not heard from for forget_robot_after_s is served as new: the
// pose its frames 2 and 3 took no longer carries its frame 4 (see
// SearchesFromAPoorPredictionThenTracksFromTheConfirmedPose), which is
// searched for again.
TEST_F(LineSetHandlerTest, ARobotSilentForForgetRobotAfterIsServedAsNew) {
  MapTileCache cache = makeCache(database_.conninfo());
  const PipelineOptions options;
  LineSetHandler handler(cache, MessageLimits{}, options);
  const PoorStart start;
  takePoorStart(handler, database_.conninfo(), start);
  handler.forgetSilentRobots(steadyClockNs());
  EXPECT_EQ(handler.counters().robots, 2u) << "the warm-up robot and the searched one";
  EXPECT_EQ(handler.counters().robots_forgotten, 0u);

  handler.forgetSilentRobots(onceSilentFor(options));
  EXPECT_EQ(handler.counters().robots, 0u);
  EXPECT_EQ(handler.counters().robots_forgotten, 2u);
  expectSearched(handler, observedEdges(database_.conninfo(), start.truth_moved),
                 start.predicted_moved, 4);
  EXPECT_EQ(handler.counters().searches, 3u);
  EXPECT_EQ(handler.counters().fixes_ok, 0u);
  EXPECT_EQ(handler.counters().robots, 1u);
}

// Serving forgets the silent robots itself: with a silence of a nanosecond,
// each LineSet forgets every other robot (and a robot heard from again is
// remembered anew).
TEST_F(LineSetHandlerTest, ServingForgetsTheRobotsSilentForForgetRobotAfter) {
  MapTileCache cache = makeCache(database_.conninfo());
  PipelineOptions options;
  options.forget_robot_after_s = 1e-9;
  LineSetHandler handler(cache, MessageLimits{}, options);
  prepareMapAt(handler, {13, -30, 1.5});
  EXPECT_EQ(handler.counters().robots, 1u);
  const PoseWithCovariance predicted = lookingNorth({13.05, -30.04, 1.5}, 0.1, 0.003);
  ASSERT_TRUE(handler.handle(lineSetMessage(fewSegments(), predicted, 3)->message()));
  EXPECT_EQ(handler.counters().robots, 1u);
  EXPECT_EQ(handler.counters().robots_forgotten, 1u);
  ASSERT_TRUE(handler.handle(lineSetMessage(fewSegments(), predicted, 4)->message()));
  EXPECT_EQ(handler.counters().robots_forgotten, 2u) << "itself, silent since its last frame";
}

// Hundreds of made-up robot ids, each asking for a search: at most
// max_robots are served, the frames of the rest answered FIX_BUSY at once and
// counted, at most max_queued_searches searches wait, and the robot tracked
// before the flood is answered with a pose at each of its frames throughout.
TEST_F(LineSetHandlerTest, ARobotKeepsBeingTrackedAmongHundredsOfMadeUpRobots) {
  MapTileCache cache = makeCache(database_.conninfo());
  PipelineOptions options;
  options.max_robots = 8;
  options.max_queued_searches = 2;
  LineSetHandler handler(cache, MessageLimits{}, options);
  const auto [seen, predicted] = trackableView(handler, database_.conninfo());
  const PoorStart start;
  uint32_t sequence = 3;
  ASSERT_EQ(handler.handle(lineSetMessage(seen, predicted, sequence++)->message())->status,
            lineloc_msg_FIX_OK);
  constexpr int kMadeUpRobots = 300;
  int searched = 0;
  int busy = 0;
  for (int robot = 0; robot < kMadeUpRobots; ++robot) {
    const auto answer = handler.handle(
        lineSetMessage(seen, start.predicted, 1, "made-up-" + std::to_string(robot))->message());
    ASSERT_TRUE(answer.has_value());
    ASSERT_TRUE(answer->status == lineloc_msg_FIX_NO_MATCH_COMPUTED ||
                answer->status == lineloc_msg_FIX_BUSY)
        << toString(answer->status);
    (answer->status == lineloc_msg_FIX_BUSY ? busy : searched) += 1;
    if (robot % 10 == 0) {
      EXPECT_EQ(handler.handle(lineSetMessage(seen, predicted, sequence++)->message())->status,
                lineloc_msg_FIX_OK)
          << "after made-up robot " << robot;
    }
  }
  const BackboneCounters counters = handler.counters();
  EXPECT_EQ(counters.robots, 8u) << "the warm-up robot, the tracked one and six made up";
  EXPECT_EQ(counters.refused_robot_frames, static_cast<uint64_t>(kMadeUpRobots - 6));
  // The tracked robot's proof searches queue beside the made-up robots'.
  EXPECT_GE(static_cast<uint64_t>(busy), counters.refused_robot_frames);
  EXPECT_LE(static_cast<uint64_t>(busy), counters.refused_robot_frames + counters.refused_searches);
  EXPECT_EQ(searched + busy, kMadeUpRobots);
  EXPECT_GE(searched, 1);
  EXPECT_LE(searched, 6);
  handler.waitForSearches();
  EXPECT_GE(handler.counters().searches, static_cast<uint64_t>(searched));
  EXPECT_EQ(handler.handle(lineSetMessage(seen, predicted, sequence++)->message())->status,
            lineloc_msg_FIX_OK);
  // Once the made-up robots are forgotten, a new robot is served.
  handler.forgetSilentRobots(onceSilentFor(options));
  EXPECT_EQ(handler.handle(lineSetMessage(seen, start.predicted, 1, "newcomer")->message())->status,
            lineloc_msg_FIX_NO_MATCH_COMPUTED);
  EXPECT_EQ(handler.counters().robots, 1u);
}

TEST_F(LineSetHandlerTest, ASearchThatDisagreesWithTheRobotsMotionIsNotConfirmed) {
  MapTileCache cache = makeCache(database_.conninfo());
  LineSetHandler handler(cache, MessageLimits{}, PipelineOptions{});
  prepareMapAt(handler, {13, -30, 1.5});
  PoorStart start;
  const std::vector<ImageSegment> seen = observedEdges(database_.conninfo(), start.truth);
  expectSearched(handler, seen, start.predicted, 2);
  // The robot believes it drove 2 m, yet the camera sees the same view.
  start.predicted.pose.translation() += Eigen::Vector3d(0.0, 2.0, 0.0);
  expectSearched(handler, seen, start.predicted, 3);
  expectSearched(handler, seen, start.predicted, 4);
  EXPECT_EQ(handler.counters().searches, 3u);
  EXPECT_EQ(handler.counters().fixes_ok, 0u);
}

TEST_F(LineSetHandlerTest, SaysWhyWhenThereIsNothingToAlign) {
  MapTileCache cache = makeCache(database_.conninfo());
  LineSetHandler handler(cache, MessageLimits{}, PipelineOptions{});
  prepareMapAt(handler, {13, -30, 1.5});
  const auto near = lineSetMessage(fewSegments(), lookingNorth({5, -20, 1.5}, 0.1, 0.003));
  EXPECT_EQ(handler.handle(near->message())->status, lineloc_msg_FIX_TOO_FEW_MATCHES);
  // Far from any prepared map: answered without a pose until the map there
  // is prepared, which holds no line.
  const auto far = lineSetMessage(fewSegments(), lookingNorth({5000, 0, 1.5}));
  EXPECT_EQ(handler.handle(far->message())->status, lineloc_msg_FIX_NO_MATCH_COMPUTED);
  handler.waitForSearches();
  EXPECT_EQ(handler.handle(far->message())->status, lineloc_msg_FIX_NO_MAP_LINES);
  EXPECT_EQ(handler.counters().answered, 4u);
}

TEST_F(LineSetHandlerTest, DropsAndCountsMalformedInputThenKeepsServing) {
  MapTileCache cache = makeCache(database_.conninfo());
  MessageLimits limits;
  limits.max_segments = 3;
  LineSetHandler handler(cache, limits, PipelineOptions{});
  const auto holder = lineSetMessage(fewSegments(), lookingNorth({5, -20, 1.5}));
  lineloc_msg_LineSet message = holder->message();
  EXPECT_FALSE(handler.handle(message).has_value());
  message.segments._length = 2;
  message.segments._buffer[1].end[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(handler.handle(message).has_value());
  EXPECT_NE(handler.counters().last_drop_reason.find("segments[1].end"), std::string::npos);
  message.segments._buffer[1].end[0] = 5.0f;
  EXPECT_TRUE(handler.handle(message).has_value());
  EXPECT_EQ(handler.counters().received, 3u);
  EXPECT_EQ(handler.counters().dropped_invalid, 2u);
  EXPECT_EQ(handler.counters().answered, 1u);
}

TEST_F(LineSetHandlerTest, UnreachableDatabaseIsAnsweredAsInternalErrorAndCounted) {
  MapTileCache cache = makeCache("host=127.0.0.1 port=1 user=nobody dbname=none connect_timeout=2");
  LineSetHandler handler(cache, MessageLimits{}, PipelineOptions{});
  const auto message = lineSetMessage(fewSegments(), lookingNorth({0, 0, 0}));
  // Answered at once while the map is loaded; the next frame learns it failed,
  // not the exposure notice before it.
  EXPECT_EQ(handler.handle(message->message())->status, lineloc_msg_FIX_NO_MATCH_COMPUTED);
  handler.waitForSearches();
  handler.handleExposure(message->message());
  const auto fix = handler.handle(message->message());
  ASSERT_TRUE(fix.has_value());
  EXPECT_EQ(fix->status, lineloc_msg_FIX_INTERNAL_ERROR);
  EXPECT_EQ(handler.counters().map_errors, 1u);
}

}  // namespace
}  // namespace lineloc
