// The DDS partition of each robot's messages. A robot writes its LineSets,
// exposure notices and states, and reads its PoseFixes, in "robot.<robot_id>"
// only; a backbone reads every robot's partition and answers each in its own.
// Under DDS Security (deploy/dds-security.sh) a robot's identity is granted its
// own partition and no other, so no participant can speak or listen for
// another robot; a backbone checks that a LineSet's robot_id is the one of the
// partition it came in (speaksFor), which access control cannot see.
#pragma once

#include <string>
#include <vector>

namespace lineloc {

inline constexpr char kRobotPartitionPrefix[] = "robot.";
// Matches every robot's partition (DDS partition names match as fnmatch patterns).
inline constexpr char kEveryRobotPartition[] = "robot.*";

std::string robotPartition(const std::string& robot_id);

// True when a message for `robot_id` was written in that robot's partition
// and no other: `writer_partitions` is the writer's partition list.
bool speaksFor(const std::vector<std::string>& writer_partitions, const std::string& robot_id);

}  // namespace lineloc
