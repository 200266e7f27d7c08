// The backbones' handovers of their robots' tracking, with real DDS
// participants on loopback: one backbone's handover reaches another (one
// queued once written, the last queued of a robot alone), and one that starts
// later; the newest by stamp is the one taken, and stays after its writer is
// gone; a backbone does not read its own back, nor one read longer ago than
// it keeps them; a malformed one is dropped.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <thread>

#include "backbone/service/tracking_handovers.h"
#include "common/messages/topics.h"
#include "tests/support/test_dds.h"
#include "tests/support/wait_for.h"

namespace lineloc {
namespace {

constexpr int64_t kKeepNs = 30'000'000'000;

TrackingHandover provenAt(int64_t stamp_ns) {
  return {.stamp_ns = stamp_ns,
          .tracking = true,
          .agreeing_proofs = 2,
          .proof_due_in_m = 0.4,
          .rival = {0.1, 0.001},
          .looked_around = true};
}

TEST(TrackingHandovers, AHandoverReachesTheOtherBackbonesAndOneThatStartsLater) {
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant west_participant(domain);
  TrackingHandovers west(west_participant, "west", kKeepNs);
  {
    dds::Participant east_participant(domain);
    TrackingHandovers east(east_participant, "east", kKeepNs);
    ASSERT_TRUE(test::waitFor([&] {
      east.publish("rover1", provenAt(2'000));
      return west.latest("rover1").has_value();
    }));
    east.queue("rover1", provenAt(3'000));
    east.queue("rover1", provenAt(3'500));
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    EXPECT_EQ(west.latest("rover1")->stamp_ns, 2'000) << "queued, not yet written";
    east.writeQueued();
    ASSERT_TRUE(test::waitFor([&] { return west.latest("rover1")->stamp_ns == 3'500; }));
    const TrackingHandover read = *west.latest("rover1");
    EXPECT_TRUE(read.tracking);
    EXPECT_EQ(read.agreeing_proofs, 2);
    EXPECT_EQ(read.proof_due_in_m, 0.4);
    EXPECT_EQ(read.rival.position_m, 0.1);
    EXPECT_EQ(read.rival.rotation_rad, 0.001);
    EXPECT_TRUE(read.looked_around);
    EXPECT_FALSE(west.latest("rover2"));

    dds::Participant north_participant(domain);
    TrackingHandovers north(north_participant, "north", kKeepNs);
    EXPECT_TRUE(test::waitFor([&] {
      const std::optional<TrackingHandover> late = north.latest("rover1");
      return late && late->stamp_ns == 3'500;
    })) << "kept for a backbone that starts later";
  }
  // East is gone, as a killed backbone is: what it handed over stays.
  ASSERT_TRUE(west.latest("rover1"));
  EXPECT_EQ(west.latest("rover1")->stamp_ns, 3'500);
}

// A robot still searched for: its acquisition's hypotheses, at most
// MAX_HANDED_HYPOTHESES of them, each read as written.
TEST(TrackingHandovers, TheHypothesesOfARobotSearchedForReachTheOtherBackbone) {
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant east_participant(domain);
  dds::Participant west_participant(domain);
  TrackingHandovers east(east_participant, "east", kKeepNs);
  TrackingHandovers west(west_participant, "west", kKeepNs);
  TrackingHandover searching{.stamp_ns = 7'000, .hypotheses = {6'500, {}}};
  for (int i = 0; i < 10; ++i) {
    searching.hypotheses.T_prediction_camera.push_back(
        Eigen::Translation3d(0.5 * i, -1.0, 0.1) *
        Eigen::AngleAxisd(0.01 * i, Eigen::Vector3d::UnitZ()));
  }
  ASSERT_TRUE(test::waitFor([&] {
    east.publish("rover1", searching);
    return west.latest("rover1").has_value();
  }));
  const TrackingHandover read = *west.latest("rover1");
  EXPECT_FALSE(read.tracking);
  EXPECT_EQ(read.hypotheses.stamp_ns, 6'500);
  ASSERT_EQ(read.hypotheses.T_prediction_camera.size(), lineloc_msg_MAX_HANDED_HYPOTHESES);
  for (size_t i = 0; i < read.hypotheses.T_prediction_camera.size(); ++i) {
    EXPECT_TRUE(read.hypotheses.T_prediction_camera[i].isApprox(
        searching.hypotheses.T_prediction_camera[i], 1e-12))
        << i;
  }
}

TEST(TrackingHandovers, ABackboneReadsNeitherItsOwnNorOnesReadLongerAgoThanItKeepsThem) {
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant east_participant(domain);
  dds::Participant west_participant(domain);
  TrackingHandovers east(east_participant, "east", kKeepNs);
  constexpr int64_t kShortKeepNs = 300'000'000;
  TrackingHandovers west(west_participant, "west", kShortKeepNs);
  ASSERT_TRUE(test::waitFor([&] {
    west.publish("rover1", provenAt(1'000));
    east.publish("rover2", provenAt(1'000));
    return west.latest("rover2").has_value() && east.latest("rover1").has_value();
  }));
  EXPECT_FALSE(west.latest("rover1")) << "its own";
  std::this_thread::sleep_for(std::chrono::nanoseconds(2 * kShortKeepNs));
  EXPECT_FALSE(west.latest("rover2")) << "read longer ago than kept";
  EXPECT_TRUE(east.latest("rover1"));
}

TEST(TrackingHandovers, AnOlderHandoverDoesNotReplaceANewerOne) {
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant east_participant(domain);
  dds::Participant west_participant(domain);
  dds::Participant south_participant(domain);
  TrackingHandovers east(east_participant, "east", kKeepNs);
  TrackingHandovers west(west_participant, "west", kKeepNs);
  TrackingHandovers south(south_participant, "south", kKeepNs);
  ASSERT_TRUE(test::waitFor([&] {
    east.publish("rover1", provenAt(5'000));
    return south.latest("rover1").has_value();
  }));
  west.publish("rover1", provenAt(4'000));
  ASSERT_TRUE(test::waitFor([&] {
    west.publish("rover2", provenAt(1'000));
    return south.latest("rover2").has_value();
  }));
  EXPECT_EQ(south.latest("rover1")->stamp_ns, 5'000);
}

// Written by one writer, in order: the valid handover last read means the
// malformed ones before it were read too.
TEST(TrackingHandovers, AMalformedHandoverIsDropped) {
  dds::Domain domain(test::testDomainId(), test::testDdsConfig());
  dds::Participant outsider_participant(domain);
  dds::Participant west_participant(domain);
  TrackingHandovers west(west_participant, "west", kKeepNs);
  dds::Writer<lineloc_msg_TrackingHandover> outsider(
      outsider_participant, dds::Qos::keptForLateReaders(1, kKeepNs), dds::kBackbonePartition);
  const auto handover = [](const char* robot_id, double rival_position_m) {
    lineloc_msg_TrackingHandover message{};
    std::snprintf(message.robot_id, sizeof(message.robot_id), "%s", robot_id);
    std::snprintf(message.backbone, sizeof(message.backbone), "%s", "outsider");
    message.stamp_ns = 1'000;
    message.tracking = true;
    message.rival_position_m = rival_position_m;
    return message;
  };
  ASSERT_TRUE(test::waitFor([&] {
    outsider.write(handover("rover1", -1.0));
    outsider.write(handover("", 0.0));
    outsider.write(handover("rover2", 0.0));
    return west.latest("rover2").has_value();
  }));
  EXPECT_FALSE(west.latest("rover1"));
  EXPECT_FALSE(west.latest(""));
}

}  // namespace
}  // namespace lineloc
