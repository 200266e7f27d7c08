// The backbone's service loop with a real PostGIS and real DDS participants
// on loopback: it refuses a site its database does not hold, and serves
// while its database is down.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <optional>
#include <thread>

#include "backbone/service/backbone_service.h"
#include "common/messages/robot_partition.h"
#include "common/messages/topics.h"
#include "common/time/clock.h"
#include "tests/support/test_database.h"
#include "tests/support/test_dds.h"

namespace lineloc {
namespace {

BackboneConfig testConfig(const std::string& conninfo, const std::string& site) {
  BackboneConfig config;
  config.domain_id = static_cast<int>(test::testDomainId());
  config.dds_config = test::testDdsConfig();
  config.db = conninfo;
  config.site = site;
  return config;
}

TEST(BackboneService, RefusesASiteItsDatabaseDoesNotHold) {
  test::TestDatabase database("backbone_service_site");
  test::insertCubeBuilding(database.conninfo(), 85000, 447000, 0, 0);
  const std::atomic<bool> stop{false};
  try {
    runBackbone(testConfig(database.conninfo(), "atlantis"), stop);
    FAIL() << "served a site the database does not hold";
  } catch (const std::runtime_error& error) {
    EXPECT_STREQ(error.what(), "site 'atlantis' is not in the database: not serving it");
  }
}

// Started while its database is down, with the sun taken from the clock over
// a site it cannot look up yet, the backbone answers a robot's frames, and
// stops when asked.
TEST(BackboneService, ServesWhileItsDatabaseIsDown) {
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant participant(domain);
  dds::Writer<lineloc_msg_LineSet> line_sets(participant, dds::Qos(dds::kHistoryDepth),
                                             robotPartition("rover1"));
  dds::Reader<lineloc_msg_PoseFix> fixes(participant, dds::poseFixQos(dds::kHistoryDepth),
                                         robotPartition("rover1"));
  BackboneConfig config =
      testConfig("host=127.0.0.1 port=1 user=nobody dbname=none connect_timeout=2", "delft");
  config.sun_from_clock = true;
  std::atomic<bool> stop{false};
  std::future<BackboneCounters> backbone =
      std::async(std::launch::async, [&] { return runBackbone(config, stop); });
  // Stops the backbone however the test ends, before the future waits for it.
  struct StopOnExit {
    std::atomic<bool>& stop;
    ~StopOnExit() { stop = true; }
  } stop_on_exit{stop};

  LineSetData data;
  data.robot_id = "rover1";
  data.stamp_ns = wallClockNs();
  data.camera = {500, 500, 320, 240, 0, 640, 480};
  data.predicted_T_world_camera.covariance = diagonalPoseCovariance(5.0, 0.2);
  const LineSetMessage message(data);
  std::optional<PoseFixData> answer;
  // Discovery takes a moment; the backbone answers each LineSet it hears.
  for (int attempt = 0; attempt < 300 && !answer; ++attempt) {
    ASSERT_NE(backbone.wait_for(std::chrono::seconds(0)), std::future_status::ready)
        << "the backbone stopped without its database";
    line_sets.write(message.message());
    if (fixes.waitForData(100'000'000)) {
      fixes.takeEach([&](const lineloc_msg_PoseFix& fix) { answer = fromMessage(fix); });
    }
  }
  ASSERT_TRUE(answer.has_value()) << "no answer in 30 s";
  EXPECT_EQ(answer->robot_id, "rover1");
  EXPECT_NE(answer->status, lineloc_msg_FIX_OK);
  stop = true;
  const BackboneCounters counters = backbone.get();
  EXPECT_GE(counters.answered, 1u);
}

}  // namespace
}  // namespace lineloc
