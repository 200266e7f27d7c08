#include "robot/ros2/ros2_wire.h"

#include <fmt/format.h>

#include <cctype>
#include <stdexcept>

namespace lineloc {

std::string ros2DdsTopic(const std::string& ros_name, const std::string& option) {
  const std::string name = ros_name.starts_with('/') ? ros_name.substr(1) : ros_name;
  const auto refuse = [&](const char* why) {
    return std::invalid_argument(
        fmt::format("{} '{}' is not a ROS 2 topic name: {}", option, ros_name, why));
  };
  if (name.empty()) {
    throw refuse("it is empty");
  }
  bool token_start = true;
  for (const char c : name) {
    if (c == '/') {
      if (token_start) {
        throw refuse("it has an empty token");
      }
      token_start = true;
      continue;
    }
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') {
      throw refuse("only letters, digits, '_' and '/' may be in it");
    }
    if (token_start && std::isdigit(static_cast<unsigned char>(c))) {
      throw refuse("a token starts with a digit");
    }
    token_start = false;
  }
  if (token_start) {
    throw refuse("it ends with '/'");
  }
  return "rt/" + name;
}

builtin_interfaces_msg_dds__Time_ rosTime(int64_t stamp_ns) {
  constexpr int64_t kNsPerSecond = 1'000'000'000;
  int64_t seconds = stamp_ns / kNsPerSecond;
  int64_t nanoseconds = stamp_ns % kNsPerSecond;
  if (nanoseconds < 0) {
    nanoseconds += kNsPerSecond;
    --seconds;
  }
  return {static_cast<int32_t>(seconds), static_cast<uint32_t>(nanoseconds)};
}

int64_t stampNs(const builtin_interfaces_msg_dds__Time_& time) {
  return static_cast<int64_t>(time.sec) * 1'000'000'000 + time.nanosec;
}

}  // namespace lineloc
