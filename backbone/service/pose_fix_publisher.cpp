#include "backbone/service/pose_fix_publisher.h"

#include <algorithm>

#include "common/messages/robot_partition.h"

namespace lineloc {

PoseFixPublisher::PoseFixPublisher(const dds::Participant& participant,
                                   int64_t keep_after_robot_left_ns)
    : participant_(participant), keep_after_robot_left_ns_(keep_after_robot_left_ns) {}

PoseFixPublisher::RobotWriter& PoseFixPublisher::writerFor(const std::string& partition) {
  RobotWriter& robot = writers_[partition];
  if (!robot.writer) {
    robot.writer = std::make_unique<dds::Writer<lineloc_msg_PoseFix>>(
        participant_, dds::poseFixQos(dds::kHistoryDepth), partition);
  }
  return robot;
}

void PoseFixPublisher::follow(const std::vector<std::string>& line_set_partitions, int64_t now_ns) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const std::string& partition : line_set_partitions) {
    if (partition.rfind(kRobotPartitionPrefix, 0) == 0 &&
        partition.size() > sizeof(kRobotPartitionPrefix) - 1) {
      writerFor(partition).last_present_ns = now_ns;
    }
  }
  for (auto robot = writers_.begin(); robot != writers_.end();) {
    const bool present =
        std::binary_search(line_set_partitions.begin(), line_set_partitions.end(), robot->first);
    if (!present && now_ns - robot->second.last_present_ns > keep_after_robot_left_ns_) {
      robot = writers_.erase(robot);
    } else {
      ++robot;
    }
  }
}

void PoseFixPublisher::publish(const PoseFixData& fix, int64_t now_ns) {
  const std::lock_guard<std::mutex> lock(mutex_);
  RobotWriter& robot = writerFor(robotPartition(fix.robot_id));
  robot.last_present_ns = now_ns;
  robot.writer->write(toMessage(fix));
}

size_t PoseFixPublisher::writers() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return writers_.size();
}

}  // namespace lineloc
