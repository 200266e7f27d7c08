// The backbone's per-robot PoseFix writers, with real DDS participants on loopback.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "backbone/service/pose_fix_publisher.h"
#include "common/messages/robot_partition.h"
#include "common/time/clock.h"
#include "tests/support/test_dds.h"
#include "tests/support/wait_for.h"

namespace lineloc {
namespace {

using test::waitFor;

constexpr int64_t kKeepNs = 1'000'000'000;

std::vector<std::string> robotIdsReceived(dds::Reader<lineloc_msg_PoseFix>& reader) {
  std::vector<std::string> robot_ids;
  reader.waitForData(200'000'000);
  reader.takeEach([&](const lineloc_msg_PoseFix& fix) { robot_ids.emplace_back(fix.robot_id); });
  return robot_ids;
}

class PoseFixPublisherTest : public ::testing::Test {
 protected:
  dds::Domain domain_{test::testDomainId(), test::testDdsConfig()};
  dds::Participant backbone_{domain_};
  dds::Participant robot_{domain_};
  PoseFixPublisher publisher_{backbone_, kKeepNs};
};

TEST_F(PoseFixPublisherTest, ARobotDiscoveredHasAWriterBeforeItsFirstAnswer) {
  dds::Reader<lineloc_msg_PoseFix> fixes(robot_, dds::poseFixQos(8), robotPartition("a"));
  publisher_.follow({robotPartition("a")}, 0);
  EXPECT_EQ(publisher_.writers(), 1u);
  EXPECT_TRUE(waitFor([&] { return fixes.matchedWriters() == 1; }));
}

TEST_F(PoseFixPublisherTest, EachRobotReceivesItsOwnAnswersOnly) {
  dds::Reader<lineloc_msg_PoseFix> fixes_of_a(robot_, dds::poseFixQos(8), robotPartition("a"));
  dds::Reader<lineloc_msg_PoseFix> fixes_of_b(robot_, dds::poseFixQos(8), robotPartition("b"));
  publisher_.follow({robotPartition("a"), robotPartition("b")}, 0);
  ASSERT_TRUE(waitFor([&] { return fixes_of_a.matchedWriters() == 1; }));
  ASSERT_TRUE(waitFor([&] { return fixes_of_b.matchedWriters() == 1; }));
  PoseFixData fix;
  fix.robot_id = "a";
  publisher_.publish(fix, 0);
  std::vector<std::string> received_by_a;
  ASSERT_TRUE(waitFor([&] {
    received_by_a = robotIdsReceived(fixes_of_a);
    return !received_by_a.empty();
  }));
  EXPECT_EQ(received_by_a, std::vector<std::string>{"a"});
  EXPECT_TRUE(robotIdsReceived(fixes_of_b).empty());
}

TEST_F(PoseFixPublisherTest, PartitionsThatAreNoRobotsGetNoWriter) {
  publisher_.follow({"", "robot.", "telemetry"}, 0);
  EXPECT_EQ(publisher_.writers(), 0u);
}

TEST_F(PoseFixPublisherTest, ARobotGoneIsDroppedAfterTheKeepTimeAndOnlyThen) {
  publisher_.follow({robotPartition("a"), robotPartition("b")}, 0);
  publisher_.follow({robotPartition("b")}, kKeepNs);
  EXPECT_EQ(publisher_.writers(), 2u) << "kept for answers on their way";
  publisher_.follow({robotPartition("b")}, kKeepNs + 1);
  EXPECT_EQ(publisher_.writers(), 1u);
}

TEST_F(PoseFixPublisherTest, AnAnswerToARobotNotYetDiscoveredCreatesItsWriter) {
  PoseFixData fix;
  fix.robot_id = "c";
  publisher_.publish(fix, 0);
  EXPECT_EQ(publisher_.writers(), 1u);
  publisher_.follow({}, kKeepNs / 2);
  EXPECT_EQ(publisher_.writers(), 1u) << "answered within the keep time";
}

}  // namespace
}  // namespace lineloc
