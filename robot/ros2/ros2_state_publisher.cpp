#include "robot/ros2/ros2_state_publisher.h"

#include <optional>

#include "robot/ros2/ros2_topics.h"
#include "robot/ros2/ros2_wire.h"

namespace lineloc {
namespace {

// ROS 2's default QoS: reliable, volatile, keep the last 10.
constexpr int32_t kRosHistoryDepth = 10;

template <typename Message>
std::optional<dds::Writer<Message>> writerOn(const dds::Participant& participant,
                                             const std::string& ros_topic, const char* option) {
  if (ros_topic.empty()) {
    return std::nullopt;
  }
  return std::optional<dds::Writer<Message>>(std::in_place, participant, dds::Qos(kRosHistoryDepth),
                                             std::string(), ros2DdsTopic(ros_topic, option));
}

// `frame_id` must outlive the header's use.
std_msgs_msg_dds__Header_ header(int64_t stamp_ns, const std::string& frame_id) {
  return {rosTime(stamp_ns), const_cast<char*>(frame_id.c_str())};
}

geometry_msgs_msg_dds__PoseWithCovariance_ rosPose(const PoseWithCovariance& pose) {
  geometry_msgs_msg_dds__PoseWithCovariance_ message{};
  const Eigen::Vector3d t = pose.pose.translation();
  const Eigen::Quaterniond q(pose.pose.linear());
  message.pose.position = {t.x(), t.y(), t.z()};
  message.pose.orientation = {q.x(), q.y(), q.z(), q.w()};
  Eigen::Map<Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(message.covariance) = pose.covariance;
  return message;
}

geometry_msgs_msg_dds__Vector3_ rosVector(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

}  // namespace

struct Ros2StatePublisher::Writers {
  std::optional<dds::Writer<geometry_msgs_msg_dds__PoseWithCovarianceStamped_>> pose;
  std::optional<dds::Writer<nav_msgs_msg_dds__Odometry_>> odometry;
  std::optional<dds::Writer<tf2_msgs_msg_dds__TFMessage_>> tf;
};

Ros2StatePublisher::Ros2StatePublisher(const dds::Participant& participant,
                                       const Ros2StateTopics& topics)
    : topics_(topics),
      writers_(std::make_unique<Writers>(Writers{
          writerOn<geometry_msgs_msg_dds__PoseWithCovarianceStamped_>(participant, topics.pose,
                                                                      "ros_pose_topic"),
          writerOn<nav_msgs_msg_dds__Odometry_>(participant, topics.odometry, "ros_odometry_topic"),
          writerOn<tf2_msgs_msg_dds__TFMessage_>(participant, topics.tf, "ros_tf_topic")})) {}

Ros2StatePublisher::~Ros2StatePublisher() = default;

void Ros2StatePublisher::publish(const BodyState& state) {
  const geometry_msgs_msg_dds__PoseWithCovariance_ pose = rosPose(state.T_map_base);
  if (writers_->pose) {
    writers_->pose->write({header(state.stamp_ns, topics_.map_frame), pose});
  }
  if (writers_->odometry) {
    nav_msgs_msg_dds__Odometry_ odometry{};
    odometry.header = header(state.stamp_ns, topics_.map_frame);
    odometry.child_frame_id = const_cast<char*>(topics_.base_frame.c_str());
    odometry.pose = pose;
    const Eigen::Matrix3d R_base_map = state.T_map_base.pose.linear().transpose();
    odometry.twist.twist.linear = rosVector(R_base_map * state.v_map_mps);
    odometry.twist.twist.angular = rosVector(state.omega_base_radps);
    Eigen::Map<Eigen::Matrix<double, 6, 6, Eigen::RowMajor>> covariance(odometry.twist.covariance);
    covariance.setZero();
    covariance.topLeftCorner<3, 3>() = R_base_map * state.v_map_covariance * R_base_map.transpose();
    covariance.bottomRightCorner<3, 3>() = state.omega_base_covariance;
    writers_->odometry->write(odometry);
  }
  if (writers_->tf) {
    geometry_msgs_msg_dds__TransformStamped_ transform{};
    transform.header = header(state.stamp_ns, topics_.map_frame);
    transform.child_frame_id = const_cast<char*>(topics_.base_frame.c_str());
    transform.transform.translation = rosVector(state.T_map_base.pose.translation());
    transform.transform.rotation = pose.pose.orientation;
    tf2_msgs_msg_dds__TFMessage_ message{};
    message.transforms._maximum = 1;
    message.transforms._length = 1;
    message.transforms._buffer = &transform;
    message.transforms._release = false;
    writers_->tf->write(message);
  }
}

}  // namespace lineloc
