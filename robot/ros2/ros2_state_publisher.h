// The robot's fused state for ROS 2, as a localiser publishes it (REP 105,
// "Coordinate Frames for Mobile Platforms"): base_link's pose in the map
// frame with its covariance (geometry_msgs/PoseWithCovarianceStamped), the
// same with base_link's velocity (nav_msgs/Odometry, its twist in base_link),
// and the map -> base_link transform on /tf (tf2_msgs/TFMessage), on ROS 2's
// DDS topics (ros2_wire.h), reliable and volatile with a history of 10, as
// ROS 2's default QoS. lineloc's pose covariance (common/geometry/pose.h:
// position, then rotation about the map's fixed axes) is ROS's; the twist's
// is turned into base_link: Sigma_v,base = R^T Sigma_v,map R.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>

#include "common/dds/dds_entities.h"
#include "common/geometry/pose.h"

namespace lineloc {

// The ROS 2 topics and frames of the state; a topic left empty is not
// published.
struct Ros2StateTopics {
  std::string pose = "/lineloc/pose";
  std::string odometry = "/lineloc/odometry";
  std::string tf = "/tf";
  std::string map_frame = "map";
  std::string base_frame = "base_link";
};

struct BodyState {
  int64_t stamp_ns = 0;
  PoseWithCovariance T_map_base;
  Eigen::Vector3d v_map_mps = Eigen::Vector3d::Zero();
  Eigen::Matrix3d v_map_covariance = Eigen::Matrix3d::Identity();
  Eigen::Vector3d omega_base_radps = Eigen::Vector3d::Zero();
  Eigen::Matrix3d omega_base_covariance = Eigen::Matrix3d::Identity();
};

class Ros2StatePublisher {
 public:
  // Throws std::invalid_argument naming the topic that is not a ROS 2 name.
  Ros2StatePublisher(const dds::Participant& participant, const Ros2StateTopics& topics);
  ~Ros2StatePublisher();
  Ros2StatePublisher(const Ros2StatePublisher&) = delete;
  Ros2StatePublisher& operator=(const Ros2StatePublisher&) = delete;

  void publish(const BodyState& state);

 private:
  struct Writers;
  Ros2StateTopics topics_;
  std::unique_ptr<Writers> writers_;
};

}  // namespace lineloc
