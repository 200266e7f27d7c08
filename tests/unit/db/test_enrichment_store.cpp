// The enrichment tables on a real PostGIS server: a pass's learnt lines become
// candidates, a second pass confirms them, writing a pass again changes
// nothing, reads and purges take what their filter names, and only the
// enricher role writes them.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "db/connection.h"
#include "db/enrichment_store.h"
#include "db/site.h"
#include "tests/support/test_database.h"

namespace lineloc::db {
namespace {

constexpr double kOriginX = 85000.0;
constexpr double kOriginY = 447000.0;
constexpr int64_t kDay_ns = 86'400'000'000'000LL;
constexpr int64_t kMonday_ns = 1'776'000'000'000'000'000LL;

// A window's top edge on the wall x = 10 (site frame), 1.2 m long at height h.
EnrichmentSighting windowTop(double height_m, const std::string& robot, int64_t seen_ns,
                             double sigma_m = 0.01) {
  EnrichmentSighting sighting;
  sighting.start_world = {10.0, 5.0, height_m};
  sighting.end_world = {10.0, 6.2, height_m};
  sighting.start_covariance = Eigen::Matrix3d::Identity() * sigma_m * sigma_m;
  sighting.end_covariance = sighting.start_covariance;
  sighting.plane_normal = -Eigen::Vector3d::UnitX();
  sighting.plane_offset = -10.0;
  sighting.robot = robot;
  sighting.views = 12;
  sighting.first_seen_ns = seen_ns;
  sighting.last_seen_ns = seen_ns + 4'000'000'000LL;
  return sighting;
}

class EnrichmentStoreTest : public ::testing::Test {
 protected:
  EnrichmentStoreTest()
      : database_("enrichment_store"),
        enricher_(database_.conninfo(test::DatabaseRole::kEnricher)) {
    Connection owner(database_.conninfo());
    ensureSite(owner, "test", 7415, {kOriginX, kOriginY, 0.0});
    site_ = requireSite(enricher_, "test");
  }

  test::TestDatabase database_;
  Connection enricher_;
  Site site_;
};

TEST_F(EnrichmentStoreTest, APassAddsCandidatesWhereTheyWereSeen) {
  const EnrichmentWriteReport report =
      writeEnrichmentPass(enricher_, site_, "monday",
                          {windowTop(3.5, "r1", kMonday_ns), windowTop(6.4, "r1", kMonday_ns)});
  EXPECT_EQ(report.added, 2);
  EXPECT_EQ(report.joined + report.already_written + report.confirmed, 0);
  const std::vector<StoredEnrichmentLine> lines = readEnrichment(enricher_, site_);
  ASSERT_EQ(lines.size(), 2u);
  const StoredEnrichmentLine& line = lines[0];
  EXPECT_LT((line.start_world - Eigen::Vector3d(10.0, 5.0, 3.5)).norm(), 1e-9);
  EXPECT_LT((line.end_world - Eigen::Vector3d(10.0, 6.2, 3.5)).norm(), 1e-9);
  EXPECT_NEAR(line.start_covariance(0, 0), 1e-4, 1e-15);
  EXPECT_EQ(line.plane_normal, -Eigen::Vector3d::UnitX());
  EXPECT_EQ(line.plane_offset, -10.0);
  EXPECT_FALSE(line.building_id.has_value());
  EXPECT_EQ(line.status, EnrichmentStatus::kCandidate);
  EXPECT_EQ(line.passes, 1);
  EXPECT_EQ(line.robots, 1);
  EXPECT_EQ(line.views, 12);
  EXPECT_EQ(line.first_seen_ns, kMonday_ns);
  EXPECT_EQ(line.last_seen_ns, kMonday_ns + 4'000'000'000LL);
  // Stored in the site's CRS, beside the model's lines.
  Connection owner(database_.conninfo());
  EXPECT_EQ(owner
                .exec("SELECT ST_SRID(geom), round(ST_X(ST_StartPoint(geom))) FROM "
                      "enrichment_line ORDER BY id LIMIT 1")
                .text(0, 1),
            "85010");
  EXPECT_EQ(owner.exec("SELECT count(*) FROM line").text(0, 0), "0");
}

TEST_F(EnrichmentStoreTest, WritingAPassAgainChangesNothing) {
  const std::vector<EnrichmentSighting> pass = {windowTop(3.5, "r1", kMonday_ns)};
  writeEnrichmentPass(enricher_, site_, "monday", pass);
  const EnrichmentWriteReport again = writeEnrichmentPass(enricher_, site_, "monday", pass);
  EXPECT_EQ(again.already_written, 1);
  EXPECT_EQ(again.added + again.joined + again.confirmed, 0);
  const std::vector<StoredEnrichmentLine> lines = readEnrichment(enricher_, site_);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].passes, 1);
  EXPECT_EQ(lines[0].views, 12);
  EXPECT_EQ(lines[0].status, EnrichmentStatus::kCandidate);
}

TEST_F(EnrichmentStoreTest, ASecondPassConfirmsAndTheMorePreciseSightingShapesTheLine) {
  writeEnrichmentPass(enricher_, site_, "monday", {windowTop(3.5, "r1", kMonday_ns, 0.02)});
  // Tuesday: 2 cm higher, more precise, and reaching 0.3 m further.
  EnrichmentSighting tuesday = windowTop(3.52, "r2", kMonday_ns + kDay_ns, 0.005);
  tuesday.end_world.y() = 6.5;
  // ... and a line 10 cm below: another edge.
  const EnrichmentWriteReport report = writeEnrichmentPass(
      enricher_, site_, "tuesday", {tuesday, windowTop(3.4, "r2", kMonday_ns + kDay_ns)});
  EXPECT_EQ(report.joined, 1);
  EXPECT_EQ(report.confirmed, 1);
  EXPECT_EQ(report.added, 1);
  EnrichmentFilter confirmed;
  confirmed.status = EnrichmentStatus::kConfirmed;
  const std::vector<StoredEnrichmentLine> lines = readEnrichment(enricher_, site_, confirmed);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NEAR(lines[0].start_world.z(), 3.52, 1e-9);
  EXPECT_NEAR(lines[0].start_world.y(), 5.0, 1e-9);
  EXPECT_NEAR(lines[0].end_world.y(), 6.5, 1e-9);
  EXPECT_NEAR(lines[0].start_covariance(0, 0), 0.005 * 0.005, 1e-15);
  EXPECT_EQ(lines[0].passes, 2);
  EXPECT_EQ(lines[0].robots, 2);
  EXPECT_EQ(lines[0].views, 24);
  EXPECT_EQ(lines[0].first_seen_ns, kMonday_ns);
  EXPECT_EQ(lines[0].last_seen_ns, kMonday_ns + kDay_ns + 4'000'000'000LL);
  EXPECT_EQ(readEnrichment(enricher_, site_).size(), 2u);
}

TEST_F(EnrichmentStoreTest, ALineMissedOnThreePassesSinceLastSeenIsRetired) {
  writeEnrichmentPass(enricher_, site_, "monday", {windowTop(3.5, "r1", kMonday_ns)});
  const int64_t id = readEnrichment(enricher_, site_).front().id;
  // Tuesday saw it; Wednesday to Friday expected it and did not.
  EnrichmentWriteReport report =
      writeEnrichmentPass(enricher_, site_, "tuesday", {windowTop(3.5, "r2", kMonday_ns + kDay_ns)},
                          {{id, kMonday_ns + kDay_ns}});
  EXPECT_EQ(report.missed, 0);
  for (int day = 2; day <= 4; ++day) {
    const std::string pass = fmt::format("day {}", day);
    report = writeEnrichmentPass(enricher_, site_, pass, {}, {{id, kMonday_ns + day * kDay_ns}});
    EXPECT_EQ(report.missed, 1) << pass;
    EXPECT_EQ(report.retired, day == 4 ? 1 : 0) << pass;
    // Written again, a pass misses nothing more.
    EXPECT_EQ(
        writeEnrichmentPass(enricher_, site_, pass, {}, {{id, kMonday_ns + day * kDay_ns}}).missed,
        0);
  }
  const std::vector<StoredEnrichmentLine> lines = readEnrichment(enricher_, site_);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].status, EnrichmentStatus::kRetired);
  // Seen there again, it is a new candidate; the retired line stays retired.
  report = writeEnrichmentPass(enricher_, site_, "saturday",
                               {windowTop(3.5, "r1", kMonday_ns + 5 * kDay_ns)});
  EXPECT_EQ(report.added, 1);
  EnrichmentFilter retired;
  retired.status = EnrichmentStatus::kRetired;
  EXPECT_EQ(readEnrichment(enricher_, site_, retired).size(), 1u);
}

TEST_F(EnrichmentStoreTest, MissesBeforeTheLastSightingDoNotRetire) {
  writeEnrichmentPass(enricher_, site_, "monday", {windowTop(3.5, "r1", kMonday_ns)});
  const int64_t id = readEnrichment(enricher_, site_).front().id;
  for (int day = 1; day <= 2; ++day) {
    writeEnrichmentPass(enricher_, site_, fmt::format("day {}", day), {},
                        {{id, kMonday_ns + day * kDay_ns}});
  }
  writeEnrichmentPass(enricher_, site_, "day 3", {windowTop(3.5, "r1", kMonday_ns + 3 * kDay_ns)});
  const EnrichmentWriteReport report =
      writeEnrichmentPass(enricher_, site_, "day 4", {}, {{id, kMonday_ns + 4 * kDay_ns}});
  EXPECT_EQ(report.missed, 1);
  EXPECT_EQ(report.retired, 0);
  EXPECT_EQ(readEnrichment(enricher_, site_).front().status, EnrichmentStatus::kConfirmed);
}

TEST_F(EnrichmentStoreTest, APassThatSawALineInAnEarlierPieceDoesNotMissIt) {
  writeEnrichmentPass(enricher_, site_, "monday", {windowTop(3.5, "r1", kMonday_ns)});
  const int64_t id = readEnrichment(enricher_, site_).front().id;
  // Monday's pass written in a second piece (another tile of the robot's
  // day) expected the line again without seeing it: no miss.
  EXPECT_EQ(writeEnrichmentPass(enricher_, site_, "monday", {}, {{id, kMonday_ns + 60'000'000'000}})
                .missed,
            0);
  EXPECT_EQ(
      writeEnrichmentPass(enricher_, site_, "tuesday", {}, {{id, kMonday_ns + kDay_ns}}).missed, 1);
}

TEST_F(EnrichmentStoreTest, ReadsAndPurgesTakeWhatTheFilterNames) {
  writeEnrichmentPass(enricher_, site_, "monday", {windowTop(3.5, "r1", kMonday_ns)});
  EnrichmentSighting far = windowTop(3.5, "r2", kMonday_ns + kDay_ns);
  far.start_world.x() = far.end_world.x() = 80.0;
  writeEnrichmentPass(enricher_, site_, "tuesday", {far});
  EnrichmentFilter area;
  area.area_world = Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(20, 20));
  ASSERT_EQ(readEnrichment(enricher_, site_, area).size(), 1u);
  EXPECT_NEAR(readEnrichment(enricher_, site_, area)[0].start_world.x(), 10.0, 1e-9);
  EnrichmentFilter robot;
  robot.robot = "r2";
  ASSERT_EQ(readEnrichment(enricher_, site_, robot).size(), 1u);
  EnrichmentFilter early;
  early.seen_before_ns = kMonday_ns + kDay_ns / 2;
  EXPECT_EQ(readEnrichment(enricher_, site_, early).size(), 1u);
  EnrichmentFilter late;
  late.seen_after_ns = kMonday_ns + kDay_ns / 2;
  EXPECT_EQ(readEnrichment(enricher_, site_, late).size(), 1u);
  EnrichmentFilter tuesday;
  tuesday.pass = "tuesday";
  EXPECT_EQ(purgeEnrichment(enricher_, site_, tuesday), 1);
  const std::vector<StoredEnrichmentLine> left = readEnrichment(enricher_, site_);
  ASSERT_EQ(left.size(), 1u);
  EXPECT_NEAR(left[0].start_world.x(), 10.0, 1e-9);
  Connection owner(database_.conninfo());
  EXPECT_EQ(owner.exec("SELECT count(*) FROM enrichment_sighting").text(0, 0), "1");
}

TEST_F(EnrichmentStoreTest, AMalformedSightingIsNamedAndNothingIsWritten) {
  EnrichmentSighting pointless = windowTop(3.5, "r1", kMonday_ns);
  pointless.end_world = pointless.start_world;
  try {
    writeEnrichmentPass(enricher_, site_, "monday", {windowTop(6.4, "r1", kMonday_ns), pointless});
    FAIL() << "a line of no length must be refused";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("sighting 1"), std::string::npos) << error.what();
  }
  EXPECT_TRUE(readEnrichment(enricher_, site_).empty());
  EXPECT_THROW(writeEnrichmentPass(enricher_, site_, "", {windowTop(3.5, "r1", kMonday_ns)}),
               std::invalid_argument);
  EXPECT_THROW(parseEnrichmentStatus("maybe"), std::invalid_argument);
  EXPECT_EQ(parseEnrichmentStatus("retired"), EnrichmentStatus::kRetired);
}

TEST_F(EnrichmentStoreTest, OnlyTheEnricherWritesAndTheReaderReads) {
  writeEnrichmentPass(enricher_, site_, "monday", {windowTop(3.5, "r1", kMonday_ns)});
  Connection writer(database_.conninfo(test::DatabaseRole::kWriter));
  EXPECT_THROW(writeEnrichmentPass(writer, site_, "tuesday", {windowTop(6.4, "r1", kMonday_ns)}),
               DatabaseError);
  const int64_t id = readEnrichment(enricher_, site_).front().id;
  EXPECT_THROW(writeEnrichmentPass(writer, site_, "tuesday", {}, {{id, kMonday_ns}}),
               DatabaseError);
  Connection reader(database_.conninfo(test::DatabaseRole::kReader));
  EXPECT_EQ(readEnrichment(reader, site_).size(), 1u);
  EXPECT_THROW(purgeEnrichment(reader, site_, {}), DatabaseError);
  // The enricher may not touch the model.
  EXPECT_THROW(enricher_.exec("DELETE FROM building"), DatabaseError);
  EXPECT_EQ(readEnrichment(enricher_, site_).size(), 1u);
}

}  // namespace
}  // namespace lineloc::db
