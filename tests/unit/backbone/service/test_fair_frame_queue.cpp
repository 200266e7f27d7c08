// The backbone's waiting frames: latest only per robot, least attained
// service first, and a flooding robot cannot delay another by more than the
// frame being answered.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "backbone/service/fair_frame_queue.h"

namespace lineloc {
namespace {

constexpr int64_t kMillisecondNs = 1'000'000;

LineSetData frame(const std::string& robot_id, uint32_t sequence_number) {
  LineSetData line_set;
  line_set.robot_id = robot_id;
  line_set.sequence_number = sequence_number;
  return line_set;
}

TEST(FairFrameQueue, ANewerFrameSupersedesTheOneItsRobotHasWaiting) {
  FairFrameQueue queue;
  EXPECT_FALSE(queue.push(frame("rover", 1), 0));
  EXPECT_FALSE(queue.push(frame("other", 7), 1));
  const std::optional<LineSetData> superseded = queue.push(frame("rover", 2), 2);
  ASSERT_TRUE(superseded);
  EXPECT_EQ(superseded->sequence_number, 1u);
  EXPECT_EQ(queue.size(), 2u);
  const auto first = queue.pop(3);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->line_set.robot_id, "other") << "taken first, at 1 ns";
  const auto second = queue.pop(3);
  ASSERT_TRUE(second);
  EXPECT_EQ(second->line_set.sequence_number, 2u);
  EXPECT_EQ(second->taken_ns, 2);
  EXPECT_FALSE(queue.pop(4));
  EXPECT_TRUE(queue.empty());
}

TEST(FairFrameQueue, TheRobotWithTheLeastRecentServiceGoesFirst) {
  FairFrameQueue queue(1.0);
  queue.charge("flood", 50 * kMillisecondNs, 0);
  queue.charge("rover", 1 * kMillisecondNs, 0);
  queue.push(frame("flood", 1), 1);
  queue.push(frame("rover", 1), 2);
  EXPECT_EQ(queue.pop(3)->line_set.robot_id, "rover");
  EXPECT_EQ(queue.pop(3)->line_set.robot_id, "flood");
}

TEST(FairFrameQueue, ServiceDecaysWithItsHalfLife) {
  FairFrameQueue queue(1.0);
  // 40 ms two half-lives ago is 10 ms now, less than 12 ms just charged.
  queue.charge("flood", 40 * kMillisecondNs, 0);
  queue.charge("rover", 12 * kMillisecondNs, 2'000 * kMillisecondNs);
  queue.push(frame("rover", 1), 2'000 * kMillisecondNs);
  queue.push(frame("flood", 1), 2'000 * kMillisecondNs + 1);
  EXPECT_EQ(queue.pop(2'000 * kMillisecondNs + 2)->line_set.robot_id, "flood");
}

TEST(FairFrameQueue, RefusesANonPositiveHalfLife) {
  EXPECT_THROW(FairFrameQueue(0.0), std::invalid_argument);
  EXPECT_THROW(FairFrameQueue(-1.0), std::invalid_argument);
}

// One server, simulated time: a flooding robot sends a frame every 10 ms
// that takes 25 ms to answer, fifteen more robot ids send one every 100 ms
// that takes 25 ms each, and a rover sends one every 100 ms that takes 2 ms.
// Once every robot has been served for a second (before, all are new to the
// queue and go in order of arrival), the rover's frames are all answered,
// each within the 25 ms frame being answered when it came plus its own 2 ms;
// the flood's excess is superseded.
TEST(FairFrameQueue, AFloodDelaysAnotherRobotByAtMostTheFrameInHand) {
  struct Sender {
    std::string robot_id;
    int64_t period_ns;
    int64_t offset_ns;
    int64_t service_ns;
    uint32_t sent = 0;
  };
  std::vector<Sender> senders = {
      {"rover", 100 * kMillisecondNs, 3 * kMillisecondNs, 2 * kMillisecondNs},
      {"flood", 10 * kMillisecondNs, 0, 25 * kMillisecondNs}};
  for (int robot = 0; robot < 15; ++robot) {
    senders.push_back({"made-up-" + std::to_string(robot), 100 * kMillisecondNs,
                       robot * 7 * kMillisecondNs, 25 * kMillisecondNs});
  }
  FairFrameQueue queue(1.0);
  int64_t now_ns = 0;
  const int64_t warm_ns = 1'000 * kMillisecondNs;
  const int64_t end_ns = 20'000 * kMillisecondNs;
  int64_t rover_worst_wait_ns = 0;
  int rover_sent = 0;
  int rover_answered = 0;
  int superseded = 0;
  const auto sendDue = [&](int64_t until_ns) {
    for (Sender& sender : senders) {
      while (sender.offset_ns + sender.sent * sender.period_ns <= until_ns) {
        const int64_t sent_ns = sender.offset_ns + sender.sent * sender.period_ns;
        rover_sent += sender.robot_id == "rover" && sent_ns >= warm_ns;
        superseded += queue.push(frame(sender.robot_id, sender.sent++), sent_ns).has_value();
      }
    }
  };
  while (now_ns < end_ns || !queue.empty()) {
    sendDue(std::min(now_ns, end_ns));
    const std::optional<FairFrameQueue::Taken> next = queue.pop(now_ns);
    if (!next) {
      now_ns += kMillisecondNs / 10;
      continue;
    }
    const Sender& sender = *std::find_if(senders.begin(), senders.end(), [&](const Sender& s) {
      return s.robot_id == next->line_set.robot_id;
    });
    if (sender.robot_id == "rover" && next->taken_ns >= warm_ns) {
      rover_worst_wait_ns = std::max(rover_worst_wait_ns, now_ns - next->taken_ns);
      ++rover_answered;
    }
    now_ns += sender.service_ns;
    queue.charge(sender.robot_id, sender.service_ns, now_ns);
  }
  EXPECT_EQ(rover_answered, rover_sent);
  EXPECT_EQ(rover_sent, 190);
  EXPECT_LE(rover_worst_wait_ns, 25 * kMillisecondNs);
  EXPECT_GT(superseded, 1000) << "the flood sends four times what one server answers";
}

}  // namespace
}  // namespace lineloc
