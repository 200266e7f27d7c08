#include "common/messages/robot_partition.h"

namespace lineloc {

std::string robotPartition(const std::string& robot_id) {
  return kRobotPartitionPrefix + robot_id;
}

bool speaksFor(const std::vector<std::string>& writer_partitions, const std::string& robot_id) {
  return writer_partitions.size() == 1 && writer_partitions.front() == robotPartition(robot_id);
}

}  // namespace lineloc
