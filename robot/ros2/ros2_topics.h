// The ROS 2 message types lineloc-robot speaks (idl/ros2.idl), each with its
// DDS type descriptor and, as the DDS topic Writer and Reader default to, the
// one of the ROS 2 topic commonly used for it (ros2DdsTopic, ros2_wire.h).
#pragma once

#include "common/dds/dds_entities.h"
#include "ros2.h"

namespace lineloc::dds {

template <>
struct TopicTraits<geometry_msgs_msg_dds__PoseWithCovarianceStamped_> {
  static constexpr const char* kName = "rt/lineloc/pose";
  static const dds_topic_descriptor_t* descriptor() {
    return &geometry_msgs_msg_dds__PoseWithCovarianceStamped__desc;
  }
};

template <>
struct TopicTraits<nav_msgs_msg_dds__Odometry_> {
  static constexpr const char* kName = "rt/lineloc/odometry";
  static const dds_topic_descriptor_t* descriptor() { return &nav_msgs_msg_dds__Odometry__desc; }
};

template <>
struct TopicTraits<tf2_msgs_msg_dds__TFMessage_> {
  static constexpr const char* kName = "rt/tf";
  static const dds_topic_descriptor_t* descriptor() { return &tf2_msgs_msg_dds__TFMessage__desc; }
};

template <>
struct TopicTraits<sensor_msgs_msg_dds__Imu_> {
  static constexpr const char* kName = "rt/imu/data";
  static const dds_topic_descriptor_t* descriptor() { return &sensor_msgs_msg_dds__Imu__desc; }
};

template <>
struct TopicTraits<sensor_msgs_msg_dds__NavSatFix_> {
  static constexpr const char* kName = "rt/fix";
  static const dds_topic_descriptor_t* descriptor() {
    return &sensor_msgs_msg_dds__NavSatFix__desc;
  }
};

template <>
struct TopicTraits<sensor_msgs_msg_dds__Image_> {
  static constexpr const char* kName = "rt/camera/image_raw";
  static const dds_topic_descriptor_t* descriptor() { return &sensor_msgs_msg_dds__Image__desc; }
};

template <>
struct TopicTraits<sensor_msgs_msg_dds__CompressedImage_> {
  static constexpr const char* kName = "rt/camera/image_raw/compressed";
  static const dds_topic_descriptor_t* descriptor() {
    return &sensor_msgs_msg_dds__CompressedImage__desc;
  }
};

}  // namespace lineloc::dds
