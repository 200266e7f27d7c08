#include "robot/agent/robot_loop.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <thread>

#include "common/config/option_values.h"
#include "common/logging/rate_limited_log.h"
#include "common/messages/message_validator.h"
#include "common/messages/robot_partition.h"
#include "common/messages/topics.h"
#include "common/time/clock.h"
#include "common/trajectory/fix_log.h"
#include "common/trajectory/pose_covariance_log.h"
#include "common/trajectory/tum_trajectory.h"
#include "robot/agent/outstanding_frames.h"
#include "robot/vision/features/feature_extractor.h"

namespace lineloc {
namespace {

// Lines a second each log of dropped input writes (rate_limited_log.h).
constexpr int kLoggedPerSecond = 5;
// How long finish() waits for answers at a time.
constexpr int64_t kPollNs = 2'000'000;

// Receives the PoseFix answers for this robot, checks them and hands the good
// ones on; records latency from each frame's exposure.
class FixReceiver {
 public:
  using Handler = std::function<void(const PoseFixData&)>;

  FixReceiver(const dds::Participant& participant, const RobotConfig& config,
              RobotRunSummary& summary, Handler handler)
      : reader_(participant, dds::poseFixQos(dds::kHistoryDepth), robotPartition(config.robot_id)),
        robot_id_(config.robot_id),
        trajectory_(config.trajectory_out),
        fix_log_(config.fix_log_out.empty() ? std::nullopt
                                            : std::make_optional<FixLogWriter>(config.fix_log_out)),
        summary_(summary),
        handler_(std::move(handler)),
        drop_log_("dropped PoseFixes", kLoggedPerSecond, 1.0) {}

  void expect(uint32_t sequence_number, const OutstandingFrames::Frame& frame) {
    outstanding_.expect(sequence_number, frame);
  }
  size_t outstanding() const { return outstanding_.size(); }
  bool answered(uint32_t sequence_number) const { return outstanding_.answered(sequence_number); }
  const dds::Reader<lineloc_msg_PoseFix>& reader() const { return reader_; }

  void poll(int64_t timeout_ns) {
    if (reader_.waitForData(timeout_ns)) {
      reader_.takeEach([this](const lineloc_msg_PoseFix& fix, const dds::SampleInfo& info) {
        receive(fix, info.source_stamp_ns);
      });
    }
  }

 private:
  // `written_wall_ns`: when the backbone wrote the answer, on its clock.
  void receive(const lineloc_msg_PoseFix& message, int64_t written_wall_ns) {
    if (robot_id_ != message.robot_id) {
      return;  // another robot's answer
    }
    if (const auto error = findPoseFixError(message)) {
      ++summary_.fixes_dropped;
      drop_log_.log("dropped a malformed PoseFix: " + *error);
      return;
    }
    const auto frame = outstanding_.take(message.sequence_number, message.stamp_ns);
    if (!frame) {
      ++summary_.fixes_dropped;
      drop_log_.log(fmt::format(
          "dropped a PoseFix for frame {} stamped {} ns: no such frame awaits an answer",
          message.sequence_number, message.stamp_ns));
      return;
    }
    const PoseFixData fix = fromMessage(message);
    const FixLatency latency =
        fixLatencyOf(*frame, steadyClockNs(), wallClockNs(), written_wall_ns, fix.timings.total);
    summary_.latency_ns.push_back(latency.total_ns);
    summary_.front_end_ns.push_back(latency.front_end_ns);
    summary_.to_backbone_ns.push_back(latency.to_backbone_ns);
    summary_.backbone_ns.push_back(latency.backbone_ns);
    summary_.from_backbone_ns.push_back(latency.back_ns);
    ++summary_.fixes_received;
    ++summary_.fixes_by_status[toString(fix.status)];
    if (fix_log_) {
      fix_log_->write({fix.stamp_ns, fix.T_world_camera, toString(fix.status), fix.inliers,
                       fix.model_lines, fix.residual_rms_px, toMilliseconds(latency.total_ns),
                       toMilliseconds(latency.front_end_ns), toMilliseconds(latency.to_backbone_ns),
                       toMilliseconds(latency.backbone_ns), toMilliseconds(latency.back_ns)});
    }
    if (fix.status == lineloc_msg_FIX_OK) {
      summary_.pose_latency_ns.push_back(latency.total_ns);
      trajectory_.write({fix.stamp_ns, fix.T_world_camera.pose});
      handler_(fix);
    }
  }

  dds::Reader<lineloc_msg_PoseFix> reader_;
  std::string robot_id_;
  TumWriter trajectory_;
  std::optional<FixLogWriter> fix_log_;
  RobotRunSummary& summary_;
  Handler handler_;
  OutstandingFrames outstanding_;
  RateLimitedLog drop_log_;
};

lineloc_msg_Health toHealth(NavigatorMode mode) {
  switch (mode) {
    case NavigatorMode::kInitialising:
      return lineloc_msg_HEALTH_INITIALISING;
    case NavigatorMode::kTracking:
      return lineloc_msg_HEALTH_TRACKING;
    case NavigatorMode::kDeadReckoning:
      return lineloc_msg_HEALTH_DEAD_RECKONING;
    case NavigatorMode::kLost:
      return lineloc_msg_HEALTH_LOST;
  }
  return lineloc_msg_HEALTH_LOST;
}

// The fused state and the navigator's health as a RobotState message.
lineloc_msg_RobotState robotState(const NavigatorEstimate& estimate, const NavigatorHealth& health,
                                  const std::string& robot_id) {
  const PoseWithCovariance T_world_body{
      makePose(estimate.state.p_world_body, estimate.state.q_world_body),
      poseBlock(estimate.covariance)};
  lineloc_msg_RobotState message{};
  copyRobotId(robot_id, message.robot_id);
  message.stamp_ns = estimate.state.stamp_ns;
  message.T_world_body = toMessage(T_world_body);
  Eigen::Map<Eigen::Vector3d>(message.velocity_world) = estimate.state.v_world_body;
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(message.velocity_covariance) =
      estimate.covariance.block<3, 3>(kVelocity, kVelocity);
  message.health = toHealth(health.mode);
  message.since_last_fix_ns = health.since_vision_fix_ns.value_or(-1);
  message.rejected_fixes = static_cast<uint32_t>(health.vision.rejected());
  message.dropped_inputs = static_cast<uint32_t>(health.imu.non_finite + health.imu.saturated +
                                                 health.imu.out_of_order + health.imu.duplicate);
  return message;
}

std::string describe(const NavigatorHealth& health) {
  return fmt::format(
      "{}, position sigma {:.3f} m, yaw sigma {:.2f} deg, vision fixes {} accepted / {} "
      "rejected, DGPS {} accepted / {} skipped / {} rejected, DGPS velocities {} accepted / {} "
      "skipped / {} rejected, compass {} accepted / {} rejected, {} restarts from vision, {} "
      "heading restarts from the compass, IMU samples dropped {}",
      toString(health.mode), health.position_sigma_m, health.yaw_sigma_rad * 180.0 / M_PI,
      health.vision.accepted, health.vision.rejected(), health.gps.accepted, health.gps.skipped,
      health.gps.rejected(), health.gps_velocity.accepted, health.gps_velocity.skipped,
      health.gps_velocity.rejected(), health.compass.accepted, health.compass.rejected(),
      health.restarts, health.heading_restarts,
      health.imu.non_finite + health.imu.saturated + health.imu.out_of_order +
          health.imu.duplicate);
}

// True when one participant both reads this robot's LineSets and writes
// PoseFixes: a backbone. Any LineSet reader would not do (a logger or monitor
// listening in would let the first frames go out before the backbone hears them).
bool backboneMatched(const dds::Writer<lineloc_msg_LineSet>& line_sets,
                     const dds::Reader<lineloc_msg_PoseFix>& fixes) {
  const std::vector<dds::ParticipantGuid> readers = line_sets.matchedReaderParticipants();
  const std::vector<dds::ParticipantGuid> writers = fixes.matchedWriterParticipants();
  return std::any_of(readers.begin(), readers.end(), [&](const dds::ParticipantGuid& reader) {
    return std::find(writers.begin(), writers.end(), reader) != writers.end();
  });
}

// The state as ROS 2 takes it: base_link's pose and velocity in the map.
BodyState bodyState(const NavigatorEstimate& estimate) {
  BodyState body;
  body.stamp_ns = estimate.state.stamp_ns;
  body.T_map_base = {makePose(estimate.state.p_world_body, estimate.state.q_world_body),
                     poseBlock(estimate.covariance)};
  body.v_map_mps = estimate.state.v_world_body;
  body.v_map_covariance = estimate.covariance.block<3, 3>(kVelocity, kVelocity);
  body.omega_base_radps = estimate.omega_body_radps;
  body.omega_base_covariance = estimate.covariance.block<3, 3>(kGyroBias, kGyroBias);
  return body;
}

}  // namespace

struct RobotLoop::Links {
  Links(const RobotConfig& config, const CameraCalibration& calibration,
        InertialNavigator* navigator, RobotRunSummary& summary)
      : domain(config.domain_id, config.dds_config),
        participant(domain),
        receiver(
            participant, config, summary,
            [navigator, &summary](const PoseFixData& fix) {
              if (navigator == nullptr) {
                return;
              }
              const MeasurementOutcome outcome = navigator->applyVisionFix(
                  fix.stamp_ns, fix.T_world_camera,
                  diagonalPoseCovariance(fix.unproven_position_sigma_m,
                                         fix.unproven_rotation_sigma_rad));
              ++(outcome == MeasurementOutcome::kAccepted || outcome == MeasurementOutcome::kPending
                     ? summary.fixes_applied
                     : summary.fixes_rejected);
            }),
        line_sets(participant, dds::Qos(dds::kHistoryDepth), robotPartition(config.robot_id)),
        exposures(participant, dds::Qos(dds::kHistoryDepth), robotPartition(config.robot_id)),
        states(participant, dds::Qos(dds::kHistoryDepth), robotPartition(config.robot_id)),
        extractor(calibration, frontEndOptions(config)),
        fused(config.fused_trajectory_out) {
    if (!config.state_log_out.empty()) {
      state_log.emplace(config.state_log_out);
    }
  }

  dds::Domain domain;
  dds::Participant participant;
  FixReceiver receiver;
  dds::Writer<lineloc_msg_LineSet> line_sets;
  dds::Writer<lineloc_msg_LineSet, dds::ExposureTopic> exposures;
  dds::Writer<lineloc_msg_RobotState> states;
  FeatureExtractor extractor;
  TumWriter fused;
  std::optional<PoseCovarianceLogWriter> state_log;
};

RobotLoop::RobotLoop(const RobotConfig& config, const CameraCalibration& calibration,
                     InertialNavigator* navigator, const dds::Participant* ros,
                     RobotRunSummary& summary)
    : config_(config),
      calibration_(calibration),
      navigator_(navigator),
      summary_(summary),
      configured_(poseOption(config.predicted_pose, config.predicted_position_sigma_m,
                             config.predicted_rotation_sigma_deg, "predicted_pose")),
      links_(std::make_unique<Links>(config, calibration, navigator, summary)),
      ros_(ros != nullptr ? std::make_unique<Ros2StatePublisher>(*ros, config.ros_state)
                          : nullptr) {
  dds::logSecurity(links_->domain);
}

RobotLoop::~RobotLoop() = default;

void RobotLoop::waitForBackbone(const std::atomic<bool>& stop) {
  const int64_t deadline =
      steadyClockNs() + static_cast<int64_t>(config_.wait_for_backbone_s * 1e9);
  const auto matched = [&] {
    return backboneMatched(links_->line_sets, links_->receiver.reader());
  };
  while (!matched() && steadyClockNs() < deadline && !stop) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!matched()) {
    spdlog::warn("no backbone found after {:.1f} s; sending anyway", config_.wait_for_backbone_s);
  }
}

void RobotLoop::addImu(const ImuSample& sample) {
  if (navigator_ != nullptr) {
    navigator_->addImu(sample);
  }
}

void RobotLoop::addGps(const GpsFix& fix) {
  if (navigator_ != nullptr) {
    navigator_->addGps(fix);
  }
}

void RobotLoop::addGpsVelocity(const GpsVelocity& velocity) {
  if (navigator_ != nullptr) {
    navigator_->addGpsVelocity(velocity);
  }
}

void RobotLoop::addCompass(const CompassReading& reading) {
  if (navigator_ != nullptr) {
    navigator_->addCompass(reading);
  }
}

std::optional<LineSetData> RobotLoop::expose(uint32_t sequence_number, int64_t stamp_ns) {
  LineSetData line_set;
  line_set.robot_id = config_.robot_id;
  line_set.sequence_number = sequence_number;
  line_set.stamp_ns = stamp_ns;
  line_set.camera = calibration_.camera;
  line_set.camera_height_m = config_.camera_height_m;
  if (navigator_ != nullptr) {
    const PosePrediction prediction = navigator_->predictAt(stamp_ns);
    if (prediction.status != PredictionStatus::kOk) {
      ++summary_.frames_before_pose;
      return std::nullopt;
    }
    if (summary_.frames_sent == 0 && summary_.frames_before_pose > 0) {
      spdlog::info("the navigator has a pose: sending from frame {}, {} held before it",
                   sequence_number, summary_.frames_before_pose);
    }
    line_set.predicted_T_world_camera = prediction.T_world_camera;
  } else {
    line_set.predicted_T_world_camera = configured_;
  }
  links_->fused.write({line_set.stamp_ns, line_set.predicted_T_world_camera.pose});
  if (config_.exposure_notices) {
    links_->exposures.write(LineSetMessage(line_set).message());
  }
  return line_set;
}

void RobotLoop::send(LineSetData& line_set, const cv::Mat& image, int64_t exposure_steady_ns) {
  const FrameFeatures& features = links_->extractor.extract(image);
  line_set.segments = features.segments;
  line_set.corners = features.corners;
  const LineSetMessage message(line_set);
  links_->receiver.expect(line_set.sequence_number,
                          {line_set.stamp_ns, exposure_steady_ns, steadyClockNs(), wallClockNs()});
  links_->line_sets.write(message.message());
  ++summary_.frames_sent;
  summary_.line_set_bytes.push_back(dds::serializedSizeBytes(message.message()));
}

void RobotLoop::poll(int64_t timeout_ns) {
  links_->receiver.poll(timeout_ns);
}

bool RobotLoop::answered(uint32_t sequence_number) const {
  return links_->receiver.answered(sequence_number);
}

void RobotLoop::publishStateIfDue() {
  if (navigator_ == nullptr || steadyClockNs() < next_state_ns_) {
    return;
  }
  if (const std::optional<NavigatorEstimate> estimate = navigator_->state()) {
    links_->states.write(robotState(*estimate, navigator_->health(), config_.robot_id));
    if (ros_) {
      ros_->publish(bodyState(*estimate));
    }
    ++summary_.states_published;
    if (links_->state_log) {
      links_->state_log->write({estimate->state.stamp_ns, navigator_->cameraPose(*estimate)});
    }
  }
  const int64_t period_ns =
      config_.state_rate_hz > 0.0 ? static_cast<int64_t>(1e9 / config_.state_rate_hz) : 0;
  next_state_ns_ = steadyClockNs() + period_ns;
}

void RobotLoop::finish(const std::atomic<bool>& stop) {
  const int64_t deadline = steadyClockNs() + static_cast<int64_t>(config_.fix_timeout_s * 1e9);
  while (links_->receiver.outstanding() > 0 && steadyClockNs() < deadline && !stop) {
    links_->receiver.poll(kPollNs);
  }
  summary_.health =
      navigator_ != nullptr ? describe(navigator_->health()) : "no IMU: fixed prediction";
}

}  // namespace lineloc
