// Topic names and type descriptors of lineloc's DDS messages (idl/lineloc.idl).
#pragma once

#include "common/dds/dds_entities.h"
#include "lineloc.h"

namespace lineloc::dds {

// Samples per robot (instance) that lineloc's writers and readers of every
// topic keep: about a second of frames at 30 Hz, for a reader woken late.
inline constexpr int32_t kHistoryDepth = 32;

template <>
struct TopicTraits<lineloc_msg_LineSet> {
  static constexpr const char* kName = "lineloc_LineSet";
  static const dds_topic_descriptor_t* descriptor() { return &lineloc_msg_LineSet_desc; }
};

// A frame's LineSet without its features, sent by the robot at the frame's
// exposure, before it extracts them: the prediction the LineSet will carry,
// so the backbone removes the hidden model lines while the robot extracts its
// image lines (line_set_handler.h). The LineSet follows on its own topic.
struct ExposureTopic {
  static constexpr const char* kName = "lineloc_Exposure";
  static const dds_topic_descriptor_t* descriptor() { return &lineloc_msg_LineSet_desc; }
};

template <>
struct TopicTraits<lineloc_msg_PoseFix> {
  static constexpr const char* kName = "lineloc_PoseFix";
  static const dds_topic_descriptor_t* descriptor() { return &lineloc_msg_PoseFix_desc; }
};

// QoS of PoseFix writers and readers. A robot starts sending once it sees
// the backbone's LineSet reader and PoseFix writer (robot_agent.cpp), but the
// backbone may meet the robot's PoseFix reader only after answering its first
// frames; kept for late readers, those answers still arrive. A second covers
// discovery under load many times over. A robot restarted within it numbers
// its frames from 0 again and may be sent the run before's answers: it takes
// an answer only with its frame's stamp (OutstandingFrames).
inline constexpr int64_t kPoseFixKeptForNs = 1'000'000'000;

inline Qos poseFixQos(int32_t history_depth) {
  return Qos::keptForLateReaders(history_depth, kPoseFixKeptForNs);
}

template <>
struct TopicTraits<lineloc_msg_RobotState> {
  static constexpr const char* kName = "lineloc_RobotState";
  static const dds_topic_descriptor_t* descriptor() { return &lineloc_msg_RobotState_desc; }
};

template <>
struct TopicTraits<lineloc_msg_BackbonePresence> {
  static constexpr const char* kName = "lineloc_Backbone";
  static const dds_topic_descriptor_t* descriptor() { return &lineloc_msg_BackbonePresence_desc; }
};

template <>
struct TopicTraits<lineloc_msg_TrackingHandover> {
  static constexpr const char* kName = "lineloc_TrackingHandover";
  static const dds_topic_descriptor_t* descriptor() { return &lineloc_msg_TrackingHandover_desc; }
};

// The partition of the backbones' presence and handovers, apart from the
// robots'.
inline constexpr char kBackbonePartition[] = "lineloc.backbones";

}  // namespace lineloc::dds
