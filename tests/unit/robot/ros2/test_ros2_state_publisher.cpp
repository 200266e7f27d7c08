// Ros2StatePublisher: what it puts on ROS 2's topics, decoded by an
// implementation of ROS 2's CDR independent of lineloc's (Foxglove's, with
// ROS 2 Humble's message definitions, tests/support/ros2_cdr), is the state
// it was given: base_link's pose in map with its covariance, the twist in
// base_link, the map -> base_link transform; and ROS 2's topic names map
// onto DDS as rmw_cyclonedds maps them.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "robot/ros2/ros2_state_publisher.h"
#include "robot/ros2/ros2_topics.h"
#include "robot/ros2/ros2_wire.h"
#include "tests/support/foxglove_cdr.h"
#include "tests/support/serialized_samples.h"
#include "tests/support/test_dds.h"

namespace lineloc {
namespace {

using test::decodedByFoxglove;

constexpr int64_t kSecondNs = 1'000'000'000;

BodyState exampleState() {
  BodyState state;
  state.stamp_ns = 1'776'159'012 * kSecondNs + 345'678'901;
  state.T_map_base.pose = Eigen::Translation3d(12.5, -3.25, 1.75) *
                          Eigen::AngleAxisd(0.6, Eigen::Vector3d(0.1, 0.2, 1.0).normalized());
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 6; ++col) {
      state.T_map_base.covariance(row, col) = row == col ? 0.01 * (row + 1) : 1e-4 * (row + col);
    }
  }
  state.v_map_mps = Eigen::Vector3d(1.2, 0.4, -0.05);
  state.v_map_covariance = Eigen::Vector3d(0.01, 0.02, 0.03).asDiagonal();
  state.omega_base_radps = Eigen::Vector3d(0.01, -0.02, 0.3);
  state.omega_base_covariance = Eigen::Vector3d(1e-6, 2e-6, 3e-6).asDiagonal();
  return state;
}

void expectStamp(const nlohmann::json& header, int64_t stamp_ns, const std::string& frame) {
  EXPECT_EQ(header["stamp"]["sec"].get<int64_t>(), stamp_ns / kSecondNs);
  EXPECT_EQ(header["stamp"]["nanosec"].get<int64_t>(), stamp_ns % kSecondNs);
  EXPECT_EQ(header["frame_id"].get<std::string>(), frame);
}

void expectPose(const nlohmann::json& pose, const PoseWithCovariance& expected) {
  const Eigen::Vector3d t = expected.pose.translation();
  const Eigen::Quaterniond q(expected.pose.linear());
  EXPECT_DOUBLE_EQ(pose["pose"]["position"]["x"].get<double>(), t.x());
  EXPECT_DOUBLE_EQ(pose["pose"]["position"]["y"].get<double>(), t.y());
  EXPECT_DOUBLE_EQ(pose["pose"]["position"]["z"].get<double>(), t.z());
  EXPECT_DOUBLE_EQ(pose["pose"]["orientation"]["x"].get<double>(), q.x());
  EXPECT_DOUBLE_EQ(pose["pose"]["orientation"]["w"].get<double>(), q.w());
  const std::vector<double> covariance = pose["covariance"].get<std::vector<double>>();
  ASSERT_EQ(covariance.size(), 36u);
  for (int i = 0; i < 36; ++i) {
    EXPECT_DOUBLE_EQ(covariance[i], expected.covariance(i / 6, i % 6)) << i;
  }
}

class Ros2StatePublisherTest : public ::testing::Test {
 protected:
  dds::Domain domain_{test::testDomainId(), test::testDdsConfig()};
  dds::Participant participant_{domain_};
};

TEST_F(Ros2StatePublisherTest, PublishesPoseOdometryAndTransformAsRos2DecodesThem) {
  Ros2StateTopics topics;
  topics.pose = "/robot7/pose";
  topics.base_frame = "robot7/base_link";
  test::SerializedReader pose_reader(
      participant_, geometry_msgs_msg_dds__PoseWithCovarianceStamped__desc, "rt/robot7/pose");
  test::SerializedReader odometry_reader(participant_, nav_msgs_msg_dds__Odometry__desc,
                                         "rt/lineloc/odometry");
  test::SerializedReader tf_reader(participant_, tf2_msgs_msg_dds__TFMessage__desc, "rt/tf");
  Ros2StatePublisher publisher(participant_, topics);
  const BodyState state = exampleState();
  publisher.publish(state);

  const auto poses = pose_reader.take(5 * kSecondNs);
  ASSERT_EQ(poses.size(), 1u);
  const nlohmann::json pose =
      decodedByFoxglove("geometry_msgs/PoseWithCovarianceStamped", poses[0]);
  expectStamp(pose["header"], state.stamp_ns, "map");
  expectPose(pose["pose"], state.T_map_base);

  const auto odometries = odometry_reader.take(5 * kSecondNs);
  ASSERT_EQ(odometries.size(), 1u);
  const nlohmann::json odometry = decodedByFoxglove("nav_msgs/Odometry", odometries[0]);
  expectStamp(odometry["header"], state.stamp_ns, "map");
  EXPECT_EQ(odometry["child_frame_id"].get<std::string>(), "robot7/base_link");
  expectPose(odometry["pose"], state.T_map_base);
  // The twist in base_link: v_base = R^T v_map.
  const Eigen::Matrix3d R = state.T_map_base.pose.linear();
  const Eigen::Vector3d v_base = R.transpose() * state.v_map_mps;
  const nlohmann::json& twist = odometry["twist"];
  EXPECT_NEAR(twist["twist"]["linear"]["x"].get<double>(), v_base.x(), 1e-12);
  EXPECT_NEAR(twist["twist"]["linear"]["y"].get<double>(), v_base.y(), 1e-12);
  EXPECT_NEAR(twist["twist"]["linear"]["z"].get<double>(), v_base.z(), 1e-12);
  EXPECT_DOUBLE_EQ(twist["twist"]["angular"]["z"].get<double>(), 0.3);
  const std::vector<double> twist_covariance = twist["covariance"].get<std::vector<double>>();
  const Eigen::Matrix3d v_base_covariance = R.transpose() * state.v_map_covariance * R;
  EXPECT_NEAR(twist_covariance[0], v_base_covariance(0, 0), 1e-15);
  EXPECT_NEAR(twist_covariance[1], v_base_covariance(0, 1), 1e-15);
  EXPECT_DOUBLE_EQ(twist_covariance[35], 3e-6);

  const auto transforms = tf_reader.take(5 * kSecondNs);
  ASSERT_EQ(transforms.size(), 1u);
  const nlohmann::json tf = decodedByFoxglove("tf2_msgs/TFMessage", transforms[0]);
  ASSERT_EQ(tf["transforms"].size(), 1u);
  const nlohmann::json& transform = tf["transforms"][0];
  expectStamp(transform["header"], state.stamp_ns, "map");
  EXPECT_EQ(transform["child_frame_id"].get<std::string>(), "robot7/base_link");
  EXPECT_DOUBLE_EQ(transform["transform"]["translation"]["x"].get<double>(), 12.5);
  EXPECT_DOUBLE_EQ(transform["transform"]["rotation"]["w"].get<double>(),
                   Eigen::Quaterniond(R).w());
}

TEST(Ros2Wire, TopicNamesMapAsRmwCycloneddsMapsThem) {
  EXPECT_EQ(ros2DdsTopic("/tf", "t"), "rt/tf");
  EXPECT_EQ(ros2DdsTopic("lineloc/pose", "t"), "rt/lineloc/pose");
  for (const std::string bad : {"", "/", "a//b", "a/", "a b", "a/1b", "ä"}) {
    try {
      ros2DdsTopic(bad, "ros_pose_topic");
      FAIL() << "'" << bad << "' taken";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("ros_pose_topic"), std::string::npos);
    }
  }
}

TEST(Ros2Wire, TimesAreSecondsAndNanosecondsOfTheEpoch) {
  const builtin_interfaces_msg_dds__Time_ time = rosTime(1'776'159'000'123'456'789);
  EXPECT_EQ(time.sec, 1'776'159'000);
  EXPECT_EQ(time.nanosec, 123'456'789u);
  EXPECT_EQ(stampNs(time), 1'776'159'000'123'456'789);
  const builtin_interfaces_msg_dds__Time_ before = rosTime(-1);
  EXPECT_EQ(before.sec, -1);
  EXPECT_EQ(before.nanosec, 999'999'999u);
  EXPECT_EQ(stampNs(before), -1);
}

}  // namespace
}  // namespace lineloc
