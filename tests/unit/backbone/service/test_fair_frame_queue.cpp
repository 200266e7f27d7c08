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

// A frame with no stamp: its robot's frame period is unknown.
LineSetData frame(const std::string& robot_id, uint32_t sequence_number) {
  LineSetData line_set;
  line_set.robot_id = robot_id;
  line_set.sequence_number = sequence_number;
  return line_set;
}

constexpr int64_t kPeriodNs = 33 * kMillisecondNs;

// Frame `k` of a robot at 30 Hz.
LineSetData frameAt30Hz(const std::string& robot_id, uint32_t k) {
  LineSetData line_set = frame(robot_id, k);
  line_set.stamp_ns = 1'000'000'000 + k * kPeriodNs;
  return line_set;
}

// Answers frames 0 and 1 of each robot alone, each in `frame_ns`: the queue
// learns their frame period and time per frame. Returns the time after.
int64_t learn(FairFrameQueue& queue, const std::vector<std::string>& robots, int64_t frame_ns) {
  int64_t now_ns = 0;
  for (uint32_t k = 0; k < 2; ++k) {
    for (const std::string& robot : robots) {
      EXPECT_FALSE(queue.push(frameAt30Hz(robot, k), now_ns).late);
      EXPECT_TRUE(queue.pop(now_ns));
      now_ns += frame_ns;
      queue.done(robot, frame_ns, now_ns);
    }
  }
  return now_ns;
}

TEST(FairFrameQueue, ANewerFrameSupersedesTheOneItsRobotHasWaiting) {
  FairFrameQueue queue;
  EXPECT_FALSE(queue.push(frame("rover", 1), 0).superseded);
  EXPECT_FALSE(queue.push(frame("other", 7), 1).superseded);
  const std::optional<LineSetData> superseded = queue.push(frame("rover", 2), 2).superseded;
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
  EXPECT_EQ(queue.size(), 0u);
}

TEST(FairFrameQueue, ARobotsNextFrameWaitsWhileItsLastIsAnswered) {
  FairFrameQueue queue(4);
  queue.push(frame("rover", 1), 0);
  ASSERT_TRUE(queue.pop(1));
  queue.push(frame("rover", 2), 2);
  queue.push(frame("other", 1), 3);
  EXPECT_EQ(queue.pop(4)->line_set.robot_id, "other");
  EXPECT_FALSE(queue.pop(5)) << "rover's frame 1 is still in hand";
  queue.done("rover", 5, 6);
  EXPECT_EQ(queue.pop(7)->line_set.sequence_number, 2u);
  EXPECT_FALSE(queue.idle());
  queue.done("rover", 1, 8);
  queue.done("other", 1, 8);
  EXPECT_TRUE(queue.idle());
}

// One thread, two robots at 30 Hz taking 20 ms a frame: while one's frame
// is answered, the other's would wait 20 ms and be answered 40 ms after it
// came, after its next frame: it is refused at once. With two threads it
// would not wait.
TEST(FairFrameQueue, AFrameThatWouldBeAnsweredAfterItsRobotsNextIsLate) {
  for (const int workers : {1, 2}) {
    FairFrameQueue queue(workers);
    const int64_t now_ns = learn(queue, {"a", "b"}, 20 * kMillisecondNs);
    EXPECT_FALSE(queue.push(frameAt30Hz("a", 2), now_ns).late);
    ASSERT_TRUE(queue.pop(now_ns));
    const FairFrameQueue::Pushed pushed = queue.push(frameAt30Hz("b", 2), now_ns + kMillisecondNs);
    EXPECT_EQ(pushed.late.has_value(), workers == 1) << workers << " workers";
    EXPECT_EQ(queue.size(), workers == 1 ? 0u : 1u);
  }
}

// Frames that fit: a frame waits for the one in hand, 5 ms of its robot's
// 33 ms period, and is queued.
TEST(FairFrameQueue, AFrameAnsweredBeforeItsRobotsNextWaits) {
  FairFrameQueue queue(1);
  const int64_t now_ns = learn(queue, {"a", "b"}, 5 * kMillisecondNs);
  queue.push(frameAt30Hz("a", 2), now_ns);
  ASSERT_TRUE(queue.pop(now_ns));
  EXPECT_FALSE(queue.push(frameAt30Hz("b", 2), now_ns).late);
  EXPECT_EQ(queue.size(), 1u);
}

// A robot slower to answer than its frame period, alone: its frames never
// wait, so each is answered, late or not; and a robot whose period is not
// known yet is never refused.
TEST(FairFrameQueue, RefusesOnlyAFrameThatWouldWait) {
  FairFrameQueue queue(1);
  int64_t now_ns = learn(queue, {"slow"}, 40 * kMillisecondNs);
  for (uint32_t k = 2; k < 6; ++k) {
    EXPECT_FALSE(queue.push(frameAt30Hz("slow", k), now_ns).late) << k;
    ASSERT_TRUE(queue.pop(now_ns));
    now_ns += 40 * kMillisecondNs;
    queue.done("slow", 40 * kMillisecondNs, now_ns);
  }
  queue.push(frameAt30Hz("slow", 6), now_ns);
  ASSERT_TRUE(queue.pop(now_ns));
  EXPECT_FALSE(queue.push(frame("new", 1), now_ns).late) << "no period known";
}

TEST(FairFrameQueue, TheRobotWithTheLeastRecentServiceGoesFirst) {
  FairFrameQueue queue(1, 1.0);
  queue.done("flood", 50 * kMillisecondNs, 0);
  queue.done("rover", 1 * kMillisecondNs, 0);
  queue.push(frame("flood", 1), 1);
  queue.push(frame("rover", 1), 2);
  EXPECT_EQ(queue.pop(3)->line_set.robot_id, "rover");
  EXPECT_EQ(queue.pop(3)->line_set.robot_id, "flood");
}

TEST(FairFrameQueue, ServiceDecaysWithItsHalfLife) {
  FairFrameQueue queue(1, 1.0);
  // 40 ms two half-lives ago is 10 ms now, less than 12 ms just charged.
  queue.done("flood", 40 * kMillisecondNs, 0);
  queue.done("rover", 12 * kMillisecondNs, 2'000 * kMillisecondNs);
  queue.push(frame("rover", 1), 2'000 * kMillisecondNs);
  queue.push(frame("flood", 1), 2'000 * kMillisecondNs + 1);
  EXPECT_EQ(queue.pop(2'000 * kMillisecondNs + 2)->line_set.robot_id, "flood");
}

TEST(FairFrameQueue, RefusesANonPositiveHalfLife) {
  EXPECT_THROW(FairFrameQueue(1, 0.0), std::invalid_argument);
  EXPECT_THROW(FairFrameQueue(1, -1.0), std::invalid_argument);
  EXPECT_THROW(FairFrameQueue(0, 1.0), std::invalid_argument);
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
  FairFrameQueue queue(1, 1.0);
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
        superseded +=
            queue.push(frame(sender.robot_id, sender.sent++), sent_ns).superseded.has_value();
      }
    }
  };
  while (now_ns < end_ns || !queue.idle()) {
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
    queue.done(sender.robot_id, sender.service_ns, now_ns);
  }
  EXPECT_EQ(rover_answered, rover_sent);
  EXPECT_EQ(rover_sent, 190);
  EXPECT_LE(rover_worst_wait_ns, 25 * kMillisecondNs);
  EXPECT_GT(superseded, 1000) << "the flood sends four times what one server answers";
}

}  // namespace
}  // namespace lineloc
