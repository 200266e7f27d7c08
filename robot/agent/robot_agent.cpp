#include "robot/agent/robot_agent.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>

#include "common/camera/camera_calibration.h"
#include "common/config/option_values.h"
#include "common/geodesy/site_projection.h"
#include "common/geometry/pose.h"
#include "common/logging/rate_limited_log.h"
#include "common/messages/message_validator.h"
#include "common/messages/messages.h"
#include "common/messages/robot_partition.h"
#include "common/messages/topics.h"
#include "common/parallel/realtime_thread.h"
#include "common/time/clock.h"
#include "common/trajectory/fix_log.h"
#include "common/trajectory/pose_covariance_log.h"
#include "common/trajectory/tum_trajectory.h"
#include "robot/agent/outstanding_frames.h"
#include "robot/agent/sensor_setup.h"
#include "robot/agent/sensor_streams.h"
#include "robot/input/image_prefetcher.h"
#include "robot/vision/features/feature_extractor.h"

namespace lineloc {
namespace {

constexpr int64_t kPollNs = 2'000'000;
// The replay decodes its next frame once the frame in flight is answered, or
// this long after its exposure when no answer comes (ImagePrefetcher): by
// then the answer is late beyond the latency it is measured against.
constexpr int64_t kDecodeUnansweredAfterNs = 15'000'000;
// Lines a second each log of dropped input writes (rate_limited_log.h).
constexpr int kLoggedPerSecond = 5;

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

void waitForBackbone(const dds::Writer<lineloc_msg_LineSet>& line_sets,
                     const dds::Reader<lineloc_msg_PoseFix>& fixes, double timeout_s,
                     const std::atomic<bool>& stop) {
  const int64_t deadline = steadyClockNs() + static_cast<int64_t>(timeout_s * 1e9);
  while (!backboneMatched(line_sets, fixes) && steadyClockNs() < deadline && !stop) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!backboneMatched(line_sets, fixes)) {
    spdlog::warn("no backbone found after {:.1f} s; sending anyway", timeout_s);
  }
}

std::unique_ptr<NmeaGpsDecoder> gpsDecoder(const RobotConfig& config) {
  if (config.site_crs.empty()) {
    return nullptr;
  }
  const std::optional<Eigen::Vector3d> origin = pointOption(config.site_origin, "site_origin");
  if (!origin) {
    throw std::invalid_argument("site_origin: x y z needed with site_crs");
  }
  return std::make_unique<NmeaGpsDecoder>(SiteProjection(config.site_crs, *origin),
                                          config.sensors.gnss_errors);
}

InertialNavigatorConfig navigatorConfig(const RobotConfig& config, const NmeaGpsDecoder* gps,
                                        const SensorStreams& streams,
                                        const std::optional<KalibrCamera>& camchain) {
  InertialNavigatorConfig navigator;
  navigator.magnetic_declination_rad = config.magnetic_declination_deg * M_PI / 180.0;
  applySensorSetup(config.sensors, streams, camchain, navigator);
  if (gps != nullptr && !streams.gps.empty()) {
    const GeodeticPosition where =
        gps->projection().toGeodetic(streams.gps.front().p_world_antenna);
    navigator.grid_bearing_of_true_north_rad = gps->projection().gridBearingOfTrueNorth_rad(where);
  }
  return navigator;
}

// Replays the timeline: each event is due at its stamp's offset from the first,
// scaled by the playback speed; frames without stamps come at rate_hz.
class Playback {
 public:
  Playback(const RobotConfig& config, int64_t first_stamp_ns)
      : first_stamp_ns_(first_stamp_ns),
        start_steady_ns_(steadyClockNs()),
        start_wall_ns_(wallClockNs()),
        speed_(config.playback_speed),
        frame_period_ns_(config.rate_hz > 0.0 ? static_cast<int64_t>(1e9 / config.rate_hz) : 0) {}

  // Steady-clock time at which the event is due.
  int64_t dueSteadyNs(const SensorEvent& event, bool stamped) const {
    if (!stamped) {
      return start_steady_ns_ + static_cast<int64_t>(event.index) * frame_period_ns_;
    }
    if (speed_ <= 0.0) {
      return 0;
    }
    return start_steady_ns_ + static_cast<int64_t>((event.stamp_ns - first_stamp_ns_) / speed_);
  }
  // False for a replay as fast as possible, which never waits for an event.
  bool paced(bool stamped) const { return stamped ? speed_ > 0.0 : frame_period_ns_ > 0; }
  // When an event due at `due_steady_ns` happened, on the steady clock (a
  // replay as fast as possible has every event happen at its start).
  int64_t happenedSteadyNs(int64_t due_steady_ns) const {
    return std::max(due_steady_ns, start_steady_ns_);
  }
  // That instant on the wall clock, as it read at the replay's start.
  int64_t wallAt(int64_t happened_steady_ns) const {
    return start_wall_ns_ + (happened_steady_ns - start_steady_ns_);
  }

 private:
  int64_t first_stamp_ns_;
  int64_t start_steady_ns_;
  int64_t start_wall_ns_;
  double speed_;
  int64_t frame_period_ns_;
};

// Raises the calling thread, the one that replays the sensors and extracts
// and sends each frame's lines, to SCHED_FIFO at `priority` (0: leaves it).
// Not for a replay as fast as possible, which never sleeps: it would keep a
// core from every time-shared thread, the robot's own receive thread too.
void runFrontEndRealtime(int priority, bool paced) {
  if (priority != 0 && !paced) {
    spdlog::warn("realtime_priority {}: ignored for a replay as fast as possible", priority);
    return;
  }
  runThreadRealtimeLogged(priority, "front end");
}

}  // namespace

FeatureExtractorOptions frontEndOptions(const RobotConfig& config) {
  FeatureExtractorOptions options;
  options.lines.min_length_px = config.min_segment_length_px;
  options.edges.min_gradient = static_cast<float>(config.min_edge_gradient);
  options.lines.min_contrast = config.min_segment_contrast;
  options.corners_on_own_thread = config.corners_on_own_thread;
  return options;
}

RobotRunSummary runRobot(const RobotConfig& config, const std::atomic<bool>& stop) {
  if (!isValidRobotId(config.robot_id)) {
    throw std::runtime_error(
        fmt::format("robot_id '{}' must match [A-Za-z0-9][A-Za-z0-9_.-]* (at most 32 characters)",
                    config.robot_id));
  }
  requireRealtimePriority(config.realtime_priority);
  if (config.camera_calibration.empty()) {
    throw std::runtime_error("calibration: a camera calibration file is required");
  }
  if (!(config.start_at_s >= 0.0 && config.start_at_s < 1e9)) {
    throw std::runtime_error(
        fmt::format("start_at_s must be >= 0 seconds, got {}", config.start_at_s));
  }
  const CameraCalibration calibration = readCameraCalibration(config.camera_calibration);
  const std::optional<KalibrCamera> camchain = readKalibrCamera(config.camera_calibration);
  const PoseWithCovariance configured =
      poseOption(config.predicted_pose, config.predicted_position_sigma_m,
                 config.predicted_rotation_sigma_deg, "predicted_pose");
  const std::optional<PoseWithCovariance> start_pose =
      config.start_pose.empty()
          ? std::nullopt
          : std::optional(poseOption(config.start_pose, config.start_position_sigma_m,
                                     config.start_rotation_sigma_deg, "start_pose"));
  const std::unique_ptr<NmeaGpsDecoder> gps = gpsDecoder(config);
  SensorStreams streams = loadSensorStreams(config.images, gps.get(),
                                            {static_cast<int64_t>(config.start_at_s * 1e9),
                                             cameraTimeOffsetNs(config.sensors, camchain)});
  requireNavigationSensors(config.images, streams, gps != nullptr, start_pose.has_value());
  for (const std::string& reason : streams.drop_reasons) {
    spdlog::warn("input dropped: {}", reason);
  }
  std::optional<InertialNavigator> navigator;
  if (!streams.imu.empty()) {
    navigator.emplace(navigatorConfig(config, gps.get(), streams, camchain));
    if (start_pose) {
      navigator->setStartPose(*start_pose);
    }
  }
  FeatureExtractor extractor(calibration, frontEndOptions(config));

  RobotRunSummary summary;
  summary.sensor_lines_dropped = streams.dropped_lines;
  RateLimitedLog skipped_frames_log("skipped frames", kLoggedPerSecond, 1.0);
  dds::Domain domain(config.domain_id, config.dds_config);
  dds::logSecurity(domain);
  dds::Participant participant(domain);
  FixReceiver receiver(participant, config, summary, [&](const PoseFixData& fix) {
    if (!navigator) {
      return;
    }
    const MeasurementOutcome outcome = navigator->applyVisionFix(
        fix.stamp_ns, fix.T_world_camera,
        diagonalPoseCovariance(fix.unproven_position_sigma_m, fix.unproven_rotation_sigma_rad));
    ++(outcome == MeasurementOutcome::kAccepted || outcome == MeasurementOutcome::kPending
           ? summary.fixes_applied
           : summary.fixes_rejected);
  });
  const std::string partition = robotPartition(config.robot_id);
  dds::Writer<lineloc_msg_LineSet> writer(participant, dds::Qos(dds::kHistoryDepth), partition);
  dds::Writer<lineloc_msg_LineSet, dds::ExposureTopic> exposure_writer(
      participant, dds::Qos(dds::kHistoryDepth), partition);
  dds::Writer<lineloc_msg_RobotState> state_writer(participant, dds::Qos(dds::kHistoryDepth),
                                                   partition);
  TumWriter fused(config.fused_trajectory_out);
  std::optional<PoseCovarianceLogWriter> state_log;
  if (!config.state_log_out.empty()) {
    state_log.emplace(config.state_log_out);
  }
  waitForBackbone(writer, receiver.reader(), config.wait_for_backbone_s, stop);

  const bool stamped = !streams.frames.empty() && streams.frames.front().stamp_ns.has_value();
  // Frames are decoded ahead of their exposure, as a camera driver delivers them.
  ImagePrefetcher images(streams.frames);
  const Playback playback(config, streams.timeline.empty() ? 0 : streams.timeline.front().stamp_ns);
  // After the decoding and DDS threads have started, which stay time-shared.
  runFrontEndRealtime(config.realtime_priority, playback.paced(stamped));
  const int64_t state_period_ns =
      config.state_rate_hz > 0.0 ? static_cast<int64_t>(1e9 / config.state_rate_hz) : 0;
  int64_t next_state_ns = 0;
  int frames_done = 0;
  // The frame whose answer the replay's decoding ahead waits for.
  struct FrameInFlight {
    bool waiting = false;
    uint32_t sequence_number = 0;
    int64_t decode_anyway_ns = 0;
  } in_flight;
  for (const SensorEvent& event : streams.timeline) {
    if (stop || (config.max_frames > 0 && frames_done >= config.max_frames)) {
      break;
    }
    const int64_t due_ns = playback.dueSteadyNs(event, stamped);
    do {
      receiver.poll(std::clamp<int64_t>(due_ns - steadyClockNs(), 0, kPollNs));
      if (in_flight.waiting && (receiver.answered(in_flight.sequence_number) ||
                                steadyClockNs() >= in_flight.decode_anyway_ns)) {
        images.resume();
        in_flight.waiting = false;
      }
    } while (steadyClockNs() < due_ns && !stop);
    switch (event.kind) {
      case SensorKind::kImu:
        navigator->addImu(streams.imu[event.index]);
        break;
      case SensorKind::kGps:
        if (navigator)
          navigator->addGps(streams.gps[event.index]);
        break;
      case SensorKind::kGpsVelocity:
        if (navigator)
          navigator->addGpsVelocity(streams.gps_velocity[event.index]);
        break;
      case SensorKind::kCompass:
        if (navigator)
          navigator->addCompass(streams.compass[event.index]);
        break;
      case SensorKind::kFrame: {
        ++frames_done;
        const FrameRef& frame = streams.frames[event.index];
        const int64_t exposure_steady_ns = playback.happenedSteadyNs(due_ns);
        LineSetData line_set;
        line_set.robot_id = config.robot_id;
        line_set.sequence_number = static_cast<uint32_t>(event.index);
        line_set.stamp_ns = frame.stamp_ns.value_or(playback.wallAt(exposure_steady_ns));
        line_set.camera = calibration.camera;
        line_set.camera_height_m = config.camera_height_m;
        if (navigator) {
          const PosePrediction prediction = navigator->predictAt(line_set.stamp_ns);
          if (prediction.status != PredictionStatus::kOk) {
            ++summary.frames_before_pose;
            break;
          }
          if (summary.frames_sent == 0 && summary.frames_before_pose > 0) {
            spdlog::info("the navigator has a pose: sending from frame {}, {} held before it",
                         event.index, summary.frames_before_pose);
          }
          line_set.predicted_T_world_camera = prediction.T_world_camera;
        } else {
          line_set.predicted_T_world_camera = configured;
        }
        fused.write({line_set.stamp_ns, line_set.predicted_T_world_camera.pose});
        if (config.exposure_notices) {
          exposure_writer.write(LineSetMessage(line_set).message());
        }
        cv::Mat image;
        try {
          image = images.take(event.index);
        } catch (const std::exception& error) {
          ++summary.frames_skipped;
          skipped_frames_log.log(fmt::format("skipped frame {}: {}", event.index, error.what()));
          images.resume();
          break;
        }
        const FrameFeatures& features = extractor.extract(image);
        line_set.segments = features.segments;
        line_set.corners = features.corners;
        const LineSetMessage message(line_set);
        receiver.expect(line_set.sequence_number,
                        {line_set.stamp_ns, exposure_steady_ns, steadyClockNs(), wallClockNs()});
        writer.write(message.message());
        in_flight = {true, line_set.sequence_number, due_ns + kDecodeUnansweredAfterNs};
        ++summary.frames_sent;
        summary.line_set_bytes.push_back(dds::serializedSizeBytes(message.message()));
        break;
      }
    }
    if (navigator && steadyClockNs() >= next_state_ns) {
      if (const std::optional<NavigatorEstimate> estimate = navigator->state()) {
        state_writer.write(robotState(*estimate, navigator->health(), config.robot_id));
        ++summary.states_published;
        if (state_log) {
          state_log->write({estimate->state.stamp_ns, navigator->cameraPose(*estimate)});
        }
      }
      next_state_ns = steadyClockNs() + state_period_ns;
    }
  }
  const int64_t deadline = steadyClockNs() + static_cast<int64_t>(config.fix_timeout_s * 1e9);
  while (receiver.outstanding() > 0 && steadyClockNs() < deadline && !stop) {
    receiver.poll(kPollNs);
  }
  summary.health = navigator ? describe(navigator->health()) : "no IMU: fixed prediction";
  return summary;
}

}  // namespace lineloc
