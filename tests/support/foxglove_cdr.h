// ROS 2 messages encoded and decoded by Foxglove's implementation of ROS 2's
// CDR with ROS 2 Humble's definitions (tests/support/ros2_cdr, run by node),
// an implementation independent of lineloc's and Cyclone DDS's.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lineloc::test {

// `bytes` (with their CDR encapsulation header) decoded as ROS 2 message
// `type` ("geometry_msgs/PoseWithCovarianceStamped"). Numeric arrays come as
// JSON arrays, byte arrays as {"base64": ...}. Throws std::runtime_error with
// node's output when it cannot decode them.
nlohmann::json decodedByFoxglove(const std::string& type, const std::vector<uint8_t>& bytes);

// `message` encoded as ROS 2 message `type`; byte arrays given as {"base64": ...}.
std::vector<uint8_t> encodedByFoxglove(const std::string& type, const nlohmann::json& message);

}  // namespace lineloc::test
