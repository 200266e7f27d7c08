// Conversions between Eigen types and the IDL structs, and the message validator.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <vector>

#include "common/messages/message_validator.h"
#include "common/messages/messages.h"

namespace lineloc {
namespace {

LineSetData makeLineSet(int segment_count) {
  LineSetData data;
  data.robot_id = "rover-7.a_b";
  data.sequence_number = 42;
  data.stamp_ns = 1'700'000'000'123'456'789;
  data.camera = {500.0, 501.0, 320.5, 240.5, 0.0, 640, 480};
  for (int i = 0; i < segment_count; ++i) {
    ImageSegment segment;
    segment.start = {10.0f + i, 20.0f};
    segment.end = {100.0f, 200.0f + i};
    segment.start_covariance << 0.5f, 0.1f, 0.1f, 0.7f;
    segment.contrast = 33.0f;
    segment.polarity = i % 2 == 0 ? 1 : -1;
    data.segments.push_back(segment);
  }
  data.corners.push_back({{50.0f, 60.0f}, Eigen::Matrix2f::Identity() * 0.04f, 7.0f});
  data.predicted_T_world_camera.pose = makePose(
      {1.0, 2.0, 3.0}, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())));
  data.predicted_T_world_camera.covariance = diagonalPoseCovariance(2.0, 0.1);
  data.camera_height_m = 1.5;
  return data;
}

TEST(Messages, LineSetRoundTripKeepsEveryField) {
  const LineSetData data = makeLineSet(3);
  const LineSetMessage message(data);
  const LineSetData back = fromMessage(message.message());
  EXPECT_EQ(back.robot_id, data.robot_id);
  EXPECT_EQ(back.sequence_number, data.sequence_number);
  EXPECT_EQ(back.stamp_ns, data.stamp_ns);
  EXPECT_EQ(back.camera.width, 640);
  EXPECT_EQ(back.camera_height_m, 1.5);
  EXPECT_DOUBLE_EQ(back.camera.fy, 501.0);
  ASSERT_EQ(back.segments.size(), 3u);
  EXPECT_EQ(back.segments[1].start, data.segments[1].start);
  EXPECT_EQ(back.segments[1].polarity, -1);
  EXPECT_TRUE(back.segments[0].start_covariance.isApprox(data.segments[0].start_covariance));
  ASSERT_EQ(back.corners.size(), 1u);
  EXPECT_FLOAT_EQ(back.corners[0].strength, 7.0f);
  EXPECT_TRUE(
      back.predicted_T_world_camera.pose.isApprox(data.predicted_T_world_camera.pose, 1e-12));
  EXPECT_TRUE(
      back.predicted_T_world_camera.covariance.isApprox(data.predicted_T_world_camera.covariance));
}

TEST(Messages, PoseFixRoundTrip) {
  PoseFixData fix;
  fix.robot_id = "r1";
  fix.sequence_number = 9;
  fix.stamp_ns = 123;
  fix.status = lineloc_msg_FIX_OK;
  fix.inliers = 17;
  fix.timings.map = 1000;
  fix.T_world_camera.pose = makePose({4, 5, 6}, Eigen::Quaterniond::Identity());
  const PoseFixData back = fromMessage(toMessage(fix));
  EXPECT_EQ(back.robot_id, "r1");
  EXPECT_EQ(back.status, lineloc_msg_FIX_OK);
  EXPECT_EQ(back.inliers, 17u);
  EXPECT_EQ(back.timings.map, 1000);
  EXPECT_TRUE(back.T_world_camera.pose.isApprox(fix.T_world_camera.pose));
  EXPECT_STREQ(toString(back.status), "ok");
}

TEST(Messages, RobotIdTooLongIsRefused) {
  PoseFixData fix;
  fix.robot_id = std::string(33, 'a');
  EXPECT_THROW(toMessage(fix), std::invalid_argument);
}

TEST(Validator, RobotIdFormat) {
  EXPECT_TRUE(isValidRobotId("robot1"));
  EXPECT_TRUE(isValidRobotId("A-b_c.9"));
  EXPECT_TRUE(isValidRobotId(std::string(32, 'x')));
  EXPECT_FALSE(isValidRobotId(""));
  EXPECT_FALSE(isValidRobotId("-leading"));
  EXPECT_FALSE(isValidRobotId("has space"));
  EXPECT_FALSE(isValidRobotId("semi;colon"));
  EXPECT_FALSE(isValidRobotId(std::string(33, 'x')));
}

TEST(Validator, AcceptsAWellFormedLineSet) {
  const LineSetMessage message(makeLineSet(5));
  EXPECT_EQ(findLineSetError(message.message(), MessageLimits{}), std::nullopt);
}

// Each corruption must be caught, and the message must name the field at fault.
struct Corruption {
  const char* name;
  void (*apply)(LineSetData&);
  const char* expected_in_error;
};

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

const Corruption kCorruptions[] = {
    {"nan_segment", [](LineSetData& d) { d.segments[2].end.x() = kNaN; }, "segments[2].end"},
    {"inf_contrast", [](LineSetData& d) { d.segments[1].contrast = INFINITY; }, "segments[1]"},
    {"outside_image", [](LineSetData& d) { d.segments[0].start.y() = 5000.0f; },
     "segments[0].start"},
    {"bad_polarity", [](LineSetData& d) { d.segments[3].polarity = 5; }, "polarity"},
    {"negative_variance", [](LineSetData& d) { d.segments[0].end_covariance(0, 0) = -1.0f; },
     "segments[0].end"},
    {"nan_corner", [](LineSetData& d) { d.corners[0].position.x() = kNaN; }, "corners[0].position"},
    {"zero_stamp", [](LineSetData& d) { d.stamp_ns = 0; }, "stamp_ns"},
    {"zero_focal", [](LineSetData& d) { d.camera.fx = 0.0; }, "camera"},
    {"empty_image", [](LineSetData& d) { d.camera.width = 0; }, "camera"},
    {"bad_robot_id", [](LineSetData& d) { d.robot_id = "bad id!"; }, "robot_id"},
    {"nan_pose",
     [](LineSetData& d) { d.predicted_T_world_camera.pose.translation().x() = std::nan(""); },
     "predicted_T_world_camera"},
    {"asymmetric_covariance",
     [](LineSetData& d) { d.predicted_T_world_camera.covariance(0, 5) = 1.0; }, "not symmetric"},
    {"negative_covariance",
     [](LineSetData& d) { d.predicted_T_world_camera.covariance(4, 4) = -1.0; }, "negative"},
    {"nan_camera_height", [](LineSetData& d) { d.camera_height_m = kNaN; }, "camera_height_m"},
    {"negative_camera_height", [](LineSetData& d) { d.camera_height_m = -1.5; }, "camera_height_m"},
};

TEST(Validator, NamesEachMalformedField) {
  for (const Corruption& corruption : kCorruptions) {
    LineSetData data = makeLineSet(5);
    corruption.apply(data);
    const LineSetMessage message(data);
    const auto error = findLineSetError(message.message(), MessageLimits{});
    ASSERT_TRUE(error.has_value()) << corruption.name;
    EXPECT_NE(error->find(corruption.expected_in_error), std::string::npos)
        << corruption.name << ": " << *error;
  }
}

TEST(Validator, QuaternionNotOfUnitNorm) {
  const LineSetMessage message(makeLineSet(1));
  lineloc_msg_LineSet raw = message.message();
  raw.predicted_T_world_camera.pose.rotation_xyzw[3] = 2.0;
  const auto error = findLineSetError(raw, MessageLimits{});
  ASSERT_TRUE(error.has_value());
  EXPECT_NE(error->find("quaternion"), std::string::npos);
}

TEST(Validator, EnforcesTheReceiversLimits) {
  const LineSetMessage message(makeLineSet(300));
  MessageLimits limits;
  EXPECT_EQ(findLineSetError(message.message(), limits), std::nullopt);
  limits.max_segments = 299;
  const auto error = findLineSetError(message.message(), limits);
  ASSERT_TRUE(error.has_value());
  EXPECT_NE(error->find("300 segments exceed the limit of 299"), std::string::npos);
}

// One LineSet claiming a huge camera would have the backbone allocate maps of
// that size: a side or an area beyond the receiver's limits is refused.
TEST(Validator, RefusesACameraBeyondTheReceiversLimits) {
  const auto errorFor = [](uint16_t width, uint16_t height, const MessageLimits& limits) {
    LineSetData data = makeLineSet(3);
    data.camera.width = width;
    data.camera.height = height;
    const LineSetMessage message(data);
    return findLineSetError(message.message(), limits);
  };
  const MessageLimits defaults;
  EXPECT_EQ(errorFor(5472, 3648, defaults), std::nullopt) << "a 20-megapixel camera";
  const auto huge = errorFor(65535, 65535, defaults);
  ASSERT_TRUE(huge.has_value());
  EXPECT_EQ(*huge, "camera.width 65535 px exceeds the limit of 8192 px");
  const auto tall = errorFor(640, 9000, defaults);
  ASSERT_TRUE(tall.has_value());
  EXPECT_EQ(*tall, "camera.height 9000 px exceeds the limit of 8192 px");
  const auto area = errorFor(8192, 8192, defaults);
  ASSERT_TRUE(area.has_value());
  EXPECT_EQ(*area,
            "camera.width x camera.height 8192 x 8192 px (67.1 megapixels) exceed the limit of 32 "
            "megapixels");
  MessageLimits small;
  small.max_camera_side_px = 640;
  small.max_camera_megapixels = 0.3;
  EXPECT_EQ(errorFor(640, 468, small), std::nullopt);
  EXPECT_TRUE(errorFor(641, 400, small).has_value());
  EXPECT_TRUE(errorFor(640, 480, small).has_value()) << "0.307 megapixels";
}

TEST(Validator, PoseFixAndRobotState) {
  PoseFixData fix;
  fix.robot_id = "r1";
  lineloc_msg_PoseFix raw = toMessage(fix);
  EXPECT_EQ(findPoseFixError(raw), std::nullopt);
  raw.residual_rms_px = -1.0f;
  EXPECT_TRUE(findPoseFixError(raw).has_value());
  raw = toMessage(fix);
  // A peer may send any 32-bit value in an enum field.
  const int32_t unknown_status = 99;
  std::memcpy(&raw.status, &unknown_status, sizeof unknown_status);
  EXPECT_TRUE(findPoseFixError(raw).has_value());

  lineloc_msg_RobotState state{};
  copyRobotId("r1", state.robot_id);
  state.T_world_body = toMessage(PoseWithCovariance{});
  EXPECT_EQ(findRobotStateError(state), std::nullopt);
  state.velocity_world[1] = std::nan("");
  EXPECT_TRUE(findRobotStateError(state).has_value());

  lineloc_msg_TrackingHandover handover{};
  copyRobotId("r1", handover.robot_id);
  std::snprintf(handover.backbone, sizeof(handover.backbone), "%s", "east");
  EXPECT_EQ(findTrackingHandoverError(handover), std::nullopt);
  handover.proof_due_in_m = -0.5;
  EXPECT_EQ(findTrackingHandoverError(handover), std::nullopt) << "a proof search overdue";
  handover.hypothesis_count = 2;
  for (lineloc_msg_Transform& hypothesis : handover.hypotheses_T_prediction_camera) {
    hypothesis.rotation_xyzw[3] = 1.0;
  }
  handover.hypotheses_T_prediction_camera[1].translation[0] = 3.5;
  EXPECT_EQ(findTrackingHandoverError(handover), std::nullopt);
  for (const auto& spoil : std::vector<std::function<void(lineloc_msg_TrackingHandover&)>>{
           [](auto& m) { m.robot_id[0] = '\0'; }, [](auto& m) { m.backbone[0] = '-'; },
           [](auto& m) { m.agreeing_proofs = kMaxAgreeingProofs + 1; },
           [](auto& m) { m.proof_due_in_m = std::nan(""); },
           [](auto& m) { m.rival_position_m = -0.1; },
           [](auto& m) { m.rival_rotation_rad = std::numeric_limits<double>::infinity(); },
           [](auto& m) { m.hypothesis_count = lineloc_msg_MAX_HANDED_HYPOTHESES + 1; },
           [](auto& m) { m.hypotheses_T_prediction_camera[1].translation[2] = std::nan(""); },
           [](auto& m) { m.hypotheses_T_prediction_camera[0].rotation_xyzw[3] = 0.5; }}) {
    lineloc_msg_TrackingHandover spoiled = handover;
    spoil(spoiled);
    EXPECT_TRUE(findTrackingHandoverError(spoiled).has_value());
  }
}

TEST(Validator, PoseFixUnprovenPartLiesWithinItsCovariance) {
  PoseFixData fix;
  fix.robot_id = "r1";
  fix.T_world_camera.covariance = diagonalPoseCovariance(0.2, 0.01);
  fix.unproven_position_sigma_m = 0.15;
  fix.unproven_rotation_sigma_rad = 0.005;
  EXPECT_EQ(fromMessage(toMessage(fix)).unproven_position_sigma_m, 0.15);
  EXPECT_EQ(fromMessage(toMessage(fix)).unproven_rotation_sigma_rad, 0.005);
  lineloc_msg_PoseFix raw = toMessage(fix);
  EXPECT_EQ(findPoseFixError(raw), std::nullopt);
  raw.unproven_position_sigma_m = std::nan("");
  const auto not_finite = findPoseFixError(raw);
  ASSERT_TRUE(not_finite.has_value());
  EXPECT_NE(not_finite->find("unproven_position_sigma_m"), std::string::npos);
  raw = toMessage(fix);
  raw.unproven_rotation_sigma_rad = -0.001;
  EXPECT_TRUE(findPoseFixError(raw).has_value());
  raw = toMessage(fix);
  raw.T_world_camera.covariance[2 * 6 + 2] = 0.01;
  const auto too_wide = findPoseFixError(raw);
  ASSERT_TRUE(too_wide.has_value());
  EXPECT_NE(too_wide->find("axis 2"), std::string::npos) << *too_wide;
}

}  // namespace
}  // namespace lineloc
