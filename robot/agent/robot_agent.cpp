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
#include "common/parallel/realtime_thread.h"
#include "common/time/clock.h"
#include "robot/agent/robot_loop.h"
#include "robot/agent/sensor_setup.h"
#include "robot/agent/sensor_streams.h"
#include "robot/input/image_prefetcher.h"
#include "robot/input/live_sensors.h"
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

Eigen::Vector3d siteOrigin(const RobotConfig& config) {
  const std::optional<Eigen::Vector3d> origin = pointOption(config.site_origin, "site_origin");
  if (!origin) {
    throw std::invalid_argument("site_origin: x y z needed with site_crs");
  }
  return *origin;
}

std::unique_ptr<NmeaGpsDecoder> gpsDecoder(const RobotConfig& config) {
  if (config.site_crs.empty()) {
    return nullptr;
  }
  return std::make_unique<NmeaGpsDecoder>(SiteProjection(config.site_crs, siteOrigin(config)),
                                          config.sensors.gnss_errors);
}

bool rosSensors(const RobotConfig& config) {
  const Ros2SensorTopics& topics = config.ros_sensors;
  return !topics.imu.empty() || !topics.navsat.empty() || !topics.image.empty();
}

// Live: a camera, and with an IMU, which carries the pose between fixes only
// from a first position, GNSS or a start pose.
void requireLiveSensors(const RobotConfig& config, bool start_pose_given) {
  if (rosSensors(config) && config.ros_domain_id < 0) {
    throw std::runtime_error("ROS 2 sensor topics need ros_domain_id, the ROS 2 domain");
  }
  if (config.live.camera.source.empty() && config.ros_sensors.image.empty()) {
    throw std::runtime_error(
        "live sensors need a camera: camera_source, or ros_image_topic with ros_domain_id");
  }
  const bool imu = !config.live.imu_source.empty() || !config.ros_sensors.imu.empty();
  const bool gnss = !config.live.gnss_source.empty() || !config.ros_sensors.navsat.empty();
  if (imu && !gnss && !start_pose_given) {
    throw std::runtime_error(
        "a live IMU without GNSS (gnss_source, ros_navsat_topic) or start_pose: without a first "
        "position the robot never localises");
  }
}

// The ROS 2 sensor source, when topics are given.
std::vector<std::unique_ptr<LiveSource>> rosSources(const RobotConfig& config,
                                                    const dds::Participant* ros) {
  std::vector<std::unique_ptr<LiveSource>> sources;
  if (ros != nullptr && rosSensors(config)) {
    sources.push_back(std::make_unique<Ros2SensorSource>(
        *ros, config.ros_sensors,
        config.site_crs.empty()
            ? nullptr
            : std::make_unique<SiteProjection>(config.site_crs, siteOrigin(config))));
  }
  return sources;
}

InertialNavigatorConfig navigatorConfig(const RobotConfig& config, const NmeaGpsDecoder* gps,
                                        const SensorStreams& streams,
                                        const std::optional<KalibrCamera>& camchain) {
  InertialNavigatorConfig navigator;
  navigator.magnetic_declination_rad = config.magnetic_declination_deg * M_PI / 180.0;
  applySensorSetup(config.sensors, streams, camchain, navigator);
  if (gps != nullptr) {
    // Where the robot starts, or the site's origin when live.
    const GeodeticPosition where = gps->projection().toGeodetic(
        streams.gps.empty() ? Eigen::Vector3d::Zero() : streams.gps.front().p_world_antenna);
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

// Replays the dataset's timeline as it was measured (Playback), its frames
// decoded ahead by an ImagePrefetcher, as a camera driver delivers them.
void runReplay(const RobotConfig& config, const SensorStreams& streams, RobotLoop& loop,
               RobotRunSummary& summary, const std::atomic<bool>& stop) {
  RateLimitedLog skipped_frames_log("skipped frames", kLoggedPerSecond, 1.0);
  const bool stamped = !streams.frames.empty() && streams.frames.front().stamp_ns.has_value();
  ImagePrefetcher images(streams.frames);
  const Playback playback(config, streams.timeline.empty() ? 0 : streams.timeline.front().stamp_ns);
  // After the decoding and DDS threads have started, which stay time-shared.
  runFrontEndRealtime(config.realtime_priority, playback.paced(stamped));
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
      loop.poll(std::clamp<int64_t>(due_ns - steadyClockNs(), 0, kPollNs));
      if (in_flight.waiting && (loop.answered(in_flight.sequence_number) ||
                                steadyClockNs() >= in_flight.decode_anyway_ns)) {
        images.resume();
        in_flight.waiting = false;
      }
    } while (steadyClockNs() < due_ns && !stop);
    switch (event.kind) {
      case SensorKind::kImu:
        loop.addImu(streams.imu[event.index]);
        break;
      case SensorKind::kGps:
        loop.addGps(streams.gps[event.index]);
        break;
      case SensorKind::kGpsVelocity:
        loop.addGpsVelocity(streams.gps_velocity[event.index]);
        break;
      case SensorKind::kCompass:
        loop.addCompass(streams.compass[event.index]);
        break;
      case SensorKind::kFrame: {
        ++frames_done;
        const FrameRef& frame = streams.frames[event.index];
        const int64_t exposure_steady_ns = playback.happenedSteadyNs(due_ns);
        std::optional<LineSetData> line_set =
            loop.expose(static_cast<uint32_t>(event.index),
                        frame.stamp_ns.value_or(playback.wallAt(exposure_steady_ns)));
        if (!line_set) {
          break;
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
        loop.send(*line_set, image, exposure_steady_ns);
        in_flight = {true, line_set->sequence_number, due_ns + kDecodeUnansweredAfterNs};
        break;
      }
    }
    loop.publishStateIfDue();
  }
}

// Takes the live sensors' readings as they come until the camera ends.
void runLive(const RobotConfig& config, LiveSensors& sensors, const RobotTimeBase& time_base,
             RobotLoop& loop, const std::atomic<bool>& stop) {
  int frames_done = 0;
  while (!stop && !(config.max_frames > 0 && frames_done >= config.max_frames)) {
    const bool ended = sensors.cameraEnded();
    std::vector<LiveReading> readings = sensors.take(kPollNs);
    if (ended && readings.empty()) {
      break;
    }
    for (LiveReading& reading : readings) {
      if (const auto* sample = std::get_if<ImuSample>(&reading)) {
        loop.addImu(*sample);
      } else if (const auto* fix = std::get_if<GpsFix>(&reading)) {
        loop.addGps(*fix);
      } else if (const auto* velocity = std::get_if<GpsVelocity>(&reading)) {
        loop.addGpsVelocity(*velocity);
      } else if (const auto* heading = std::get_if<CompassReading>(&reading)) {
        loop.addCompass(*heading);
      } else if (auto* frame = std::get_if<LiveFrame>(&reading)) {
        ++frames_done;
        if (std::optional<LineSetData> line_set =
                loop.expose(frame->sequence, frame->captured.stamp_ns)) {
          loop.send(*line_set, frame->captured.image, time_base.toSteady(frame->captured.stamp_ns));
        }
      }
    }
    loop.poll(0);
    loop.publishStateIfDue();
  }
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
  const std::optional<PoseWithCovariance> start_pose =
      config.start_pose.empty()
          ? std::nullopt
          : std::optional(poseOption(config.start_pose, config.start_position_sigma_m,
                                     config.start_rotation_sigma_deg, "start_pose"));
  const std::unique_ptr<NmeaGpsDecoder> gps = gpsDecoder(config);
  const bool live = !config.live.camera.source.empty() || rosSensors(config);
  SensorStreams streams;
  if (live) {
    requireLiveSensors(config, start_pose.has_value());
  } else {
    streams = loadSensorStreams(config.images, gps.get(),
                                {static_cast<int64_t>(config.start_at_s * 1e9),
                                 cameraTimeOffsetNs(config.sensors, camchain)});
    requireNavigationSensors(config.images, streams, gps != nullptr, start_pose.has_value());
    for (const std::string& reason : streams.drop_reasons) {
      spdlog::warn("input dropped: {}", reason);
    }
  }
  std::optional<InertialNavigator> navigator;
  if (live ? !config.live.imu_source.empty() || !config.ros_sensors.imu.empty()
           : !streams.imu.empty()) {
    navigator.emplace(navigatorConfig(config, gps.get(), streams, camchain));
    if (start_pose) {
      navigator->setStartPose(*start_pose);
    }
  }
  RobotRunSummary summary;
  summary.sensor_lines_dropped = streams.dropped_lines;
  std::optional<dds::Domain> ros_domain;
  std::optional<dds::Participant> ros;
  if (config.ros_domain_id >= 0) {
    ros_domain.emplace(static_cast<uint32_t>(config.ros_domain_id), config.ros_dds_config);
    ros.emplace(*ros_domain);
  }
  RobotLoop loop(config, calibration, navigator ? &*navigator : nullptr, ros ? &*ros : nullptr,
                 summary);
  if (live) {
    const RobotTimeBase time_base;
    LiveSensors sensors(config.live, time_base, config.site_crs, siteOrigin(config),
                        config.sensors.gnss_errors, rosSources(config, ros ? &*ros : nullptr));
    loop.waitForBackbone(stop);
    runFrontEndRealtime(config.realtime_priority, true);
    runLive(config, sensors, time_base, loop, stop);
    const LiveSensorCounts counts = sensors.counts();
    summary.sensor_lines_dropped +=
        static_cast<int>(counts.imu_lines_dropped + counts.compass_lines_dropped +
                         counts.gnss_dropped + counts.source_dropped);
    spdlog::info(
        "live sensors: {} frames ({} dropped unread), {} IMU samples, {} compass readings, {} "
        "GNSS fixes, {} GNSS velocities",
        counts.frames, counts.frames_dropped, counts.imu_samples, counts.compass_readings,
        counts.gnss_fixes, counts.gnss_velocities);
  } else {
    loop.waitForBackbone(stop);
    runReplay(config, streams, loop, summary, stop);
  }
  loop.finish(stop);
  return summary;
}

}  // namespace lineloc
