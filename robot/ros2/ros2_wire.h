// How ROS 2 names its topics and stamps its messages on DDS, as its Cyclone
// DDS middleware (rmw_cyclonedds) does: a ROS topic /a/b is the DDS topic
// "rt/a/b" (ROS 2 design, "Topic and Service name mapping to DDS"), and a
// builtin_interfaces/Time is seconds and nanoseconds of the Unix epoch.
#pragma once

#include <cstdint>
#include <string>

#include "ros2.h"

namespace lineloc {

// The DDS topic of ROS 2 topic `ros_name` (absolute, "/tf"; or relative to
// the root namespace, "tf"). Throws std::invalid_argument naming `option`
// when the name is not a valid ROS 2 topic name: empty, with characters
// other than letters, digits, '_' and '/', an empty token ("//", a trailing
// '/'), or a token starting with a digit.
std::string ros2DdsTopic(const std::string& ros_name, const std::string& option);

// t = sec + nanosec 1e-9, nanosec in [0, 1e9).
builtin_interfaces_msg_dds__Time_ rosTime(int64_t stamp_ns);
int64_t stampNs(const builtin_interfaces_msg_dds__Time_& time);

}  // namespace lineloc
