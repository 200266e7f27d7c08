// The backbones sharing a domain, with real DDS participants on loopback:
// each sees the others alive and itself; one that leaves is no longer seen;
// a name that is none is refused; every robot is served by exactly one.
#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "backbone/service/backbone_peers.h"
#include "tests/support/test_dds.h"
#include "tests/support/wait_for.h"

namespace lineloc {
namespace {

constexpr int64_t kLeaseNs = 1'000'000'000;

using Names = std::vector<std::string>;

TEST(BackbonePeers, EachSeesTheOthersAliveAndOneThatLeavesIsGone) {
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant east_participant(domain);
  dds::Participant west_participant(domain);
  BackbonePeers east(east_participant, "east", kLeaseNs);
  EXPECT_EQ(east.refresh(), Names({"east"}));
  {
    dds::Participant north_participant(domain);
    BackbonePeers west(west_participant, "west", kLeaseNs);
    BackbonePeers north(north_participant, "north", kLeaseNs);
    ASSERT_TRUE(test::waitFor([&] {
      return east.refresh() == Names({"east", "north", "west"}) &&
             west.refresh() == Names({"east", "north", "west"}) &&
             north.refresh() == Names({"east", "north", "west"});
    })) << east.refresh().size();
    for (int robot = 0; robot < 100; ++robot) {
      const std::string robot_id = "robot-" + std::to_string(robot);
      EXPECT_EQ(east.serves(robot_id) + west.serves(robot_id) + north.serves(robot_id), 1)
          << robot_id;
    }
  }
  EXPECT_TRUE(test::waitFor([&] { return east.refresh() == Names({"east"}); }))
      << east.refresh().size();
}

TEST(BackbonePeers, RefusesANameThatIsNone) {
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant participant(domain);
  EXPECT_THROW(BackbonePeers(participant, "", kLeaseNs), std::invalid_argument);
  EXPECT_THROW(BackbonePeers(participant, "-east", kLeaseNs), std::invalid_argument);
  EXPECT_THROW(BackbonePeers(participant, "east west", kLeaseNs), std::invalid_argument);
  EXPECT_THROW(BackbonePeers(participant, std::string(65, 'a'), kLeaseNs), std::invalid_argument);
  EXPECT_THROW(BackbonePeers(participant, "east", 0), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
