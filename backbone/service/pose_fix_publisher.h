// The backbone's PoseFix writers: one per robot, in the robot's own partition
// (common/messages/robot_partition.h), so that under DDS Security each robot
// can be granted its own answers and no other robot's.
//
// A robot sends its first frame once it sees a backbone that reads its
// LineSets and writes its PoseFixes (robot_agent.cpp), so a robot's writer is
// created as soon as one of its LineSet writers is discovered (follow), not at
// its first answer. A writer whose robot has no LineSet writer left is kept
// for keep_after_robot_left_ns, long enough for answers to frames still on
// their way, then deleted: the writers held are bounded by the robots present.
// Thread-safe: fixes are published by the threads answering frames
// (frame_workers.h) while the serving loop follows the robots.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common/messages/messages.h"
#include "common/messages/topics.h"

namespace lineloc {

class PoseFixPublisher {
 public:
  PoseFixPublisher(const dds::Participant& participant, int64_t keep_after_robot_left_ns);

  // `line_set_partitions`: the partitions of the LineSet writers now
  // discovered, sorted (dds::Reader::matchedWritersPartitions); `now_ns` steady clock.
  void follow(const std::vector<std::string>& line_set_partitions, int64_t now_ns);

  // Writes `fix` in its robot's partition, creating the robot's writer if
  // follow() has not.
  void publish(const PoseFixData& fix, int64_t now_ns);

  size_t writers() const;

 private:
  struct RobotWriter {
    std::unique_ptr<dds::Writer<lineloc_msg_PoseFix>> writer;
    // When its robot was last seen with a LineSet writer, or last answered.
    int64_t last_present_ns = 0;
  };

  RobotWriter& writerFor(const std::string& partition);

  const dds::Participant& participant_;
  int64_t keep_after_robot_left_ns_;
  mutable std::mutex mutex_;
  std::map<std::string, RobotWriter> writers_;
};

}  // namespace lineloc
