// lineloc-robot: the onboard agent. Reads camera frames, sends their line
// segments to the backbone over DDS and writes the poses it gets back.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <csignal>
#include <iostream>
#include <string>
#include <vector>

#include "common/config/program_options.h"
#include "common/parallel/resident_heap.h"
#include "common/time/clock.h"
#include "common/time/percentile.h"
#include "robot/agent/robot_agent.h"

namespace {
std::atomic<bool> g_stop{false};
void requestStop(int) {
  g_stop = true;
}

// "median/p99/max" of durations, in ms.
std::string describeLatency(const std::vector<int64_t>& durations_ns) {
  return fmt::format("{:.2f}/{:.2f}/{:.1f}",
                     lineloc::toMilliseconds(lineloc::percentile(durations_ns, 50)),
                     lineloc::toMilliseconds(lineloc::percentile(durations_ns, 99)),
                     lineloc::toMilliseconds(lineloc::percentile(durations_ns, 100)));
}
// Options <prefix>_pose (tx ty tz qx qy qz qw) and its sigmas
// <prefix>_position_sigma_m and <prefix>_rotation_sigma_deg.
void addPoseOption(lineloc::ProgramOptions& options, const std::string& prefix,
                   std::vector<double>& pose, double& position_sigma_m, double& rotation_sigma_deg,
                   const std::string& what) {
  options.addFixedSize(prefix + "_pose", pose, 7, fmt::format("{}, tx ty tz qx qy qz qw", what));
  options.add(prefix + "_position_sigma_m", position_sigma_m,
              fmt::format("standard deviation of the {} position (m)", prefix));
  options.add(prefix + "_rotation_sigma_deg", rotation_sigma_deg,
              fmt::format("standard deviation of the {} rotation (degrees)", prefix));
}
}  // namespace

int main(int argc, char** argv) {
  lineloc::RobotConfig config;
  lineloc::ProgramOptions options("lineloc-robot", "lineloc onboard agent");
  options.add("robot_id", config.robot_id, "this robot's id, [A-Za-z0-9][A-Za-z0-9_.-]*");
  options.add("images", config.images,
              "EuRoC/ASL dataset (cam0/, imu0/, gps0/, compass0/), cam0/ folder or image folder");
  options.add("camera_source", config.live.camera.source,
              "live camera instead of `images`: a device index or path (V4L2), a GStreamer "
              "pipeline ending in appsink, a stream URL or a video file, played in real time");
  options.add("camera_exposure", config.live.camera.exposure,
              "live camera's exposure in its own units (V4L2: 100 us); negative: the device's");
  options.add("camera_gain", config.live.camera.gain,
              "live camera's gain in its own units; negative: the device's");
  options.add("gnss_source", config.live.gnss_source,
              "live GNSS: 'gpsd', 'gpsd:HOST:PORT', or a serial device, FIFO or file of NMEA "
              "0183 (empty: none)");
  options.add("gnss_baud", config.live.gnss_baud, "baud rate of a serial GNSS receiver");
  options.add("imu_source", config.live.imu_source,
              "live IMU: a serial device, FIFO or file of EuRoC CSV rows, timestamp_ns, w_x, "
              "w_y, w_z (rad/s), a_x, a_y, a_z (m/s^2) (empty: none)");
  options.add("imu_baud", config.live.imu_baud, "baud rate of a serial IMU");
  options.add("compass_source", config.live.compass_source,
              "live compass: a serial device, FIFO or file of CSV rows, timestamp_ns, magnetic "
              "heading (rad, clockwise from magnetic north) (empty: none)");
  options.add("compass_baud", config.live.compass_baud, "baud rate of a serial compass");
  options.add("ros_domain_id", config.ros_domain_id,
              "ROS 2 domain (ROS_DOMAIN_ID) the robot publishes its state on and reads ROS 2 "
              "sensor topics from; -1: no ROS 2");
  options.add("ros_dds_config", config.ros_dds_config,
              "Cyclone DDS configuration files of the ROS 2 domain (empty: CYCLONEDDS_URI)");
  options.add("ros_pose_topic", config.ros_state.pose,
              "ROS 2 topic of base_link's pose in map (PoseWithCovarianceStamped; empty: none)");
  options.add("ros_odometry_topic", config.ros_state.odometry,
              "ROS 2 topic of the odometry (nav_msgs/Odometry; empty: none)");
  options.add("ros_tf_topic", config.ros_state.tf,
              "ROS 2 topic of the map -> base_link transform (tf2_msgs/TFMessage; empty: none)");
  options.add("ros_map_frame", config.ros_state.map_frame, "ROS 2 frame of the site frame");
  options.add("ros_base_frame", config.ros_state.base_frame, "ROS 2 frame of the robot's body");
  options.add("ros_imu_topic", config.ros_sensors.imu,
              "live IMU from a ROS 2 sensor_msgs/Imu topic (empty: none)");
  options.add("ros_navsat_topic", config.ros_sensors.navsat,
              "live GNSS from a ROS 2 sensor_msgs/NavSatFix topic (empty: none)");
  options.add("ros_image_topic", config.ros_sensors.image,
              "live camera from a ROS 2 sensor_msgs/Image topic, or CompressedImage on a topic "
              "ending in /compressed (empty: none)");
  options.add("geoid_height_m", config.ros_sensors.geoid_height_m,
              "the geoid's height above the WGS84 ellipsoid at the site (m), subtracted from "
              "NavSatFix altitudes");
  options.add("camera_calibration", config.camera_calibration,
              "camera calibration (OpenCV YAML layout)");
  addPoseOption(options, "predicted", config.predicted_pose, config.predicted_position_sigma_m,
                config.predicted_rotation_sigma_deg, "without IMU data: predicted T_world_camera");
  addPoseOption(options, "start", config.start_pose, config.start_position_sigma_m,
                config.start_rotation_sigma_deg,
                "with IMU data and no GNSS: T_world_camera where the robot stands at its start");
  options.add("camera_height_m", config.camera_height_m,
              "height of the camera above the ground the robot stands on (m); 0: unknown. The "
              "backbone then finds the camera from DGPS and compass however poor the DGPS "
              "altitude");
  options.add("site_crs", config.site_crs, "CRS of the site frame, e.g. EPSG:7415 (for DGPS)");
  options.addFixedSize("site_origin", config.site_origin, 3, "site origin x y z in that CRS");
  options.add("magnetic_declination_deg", config.magnetic_declination_deg,
              "magnetic declination at the site, east positive (degrees)");
  lineloc::SensorSetup& sensors = config.sensors;
  options.add("gyro_noise_density", sensors.gyro_noise_density,
              "IMU gyroscope white noise (rad/s/sqrt(Hz)); 0, with the three below: the "
              "dataset's imu0/sensor.yaml, else an ADIS16448's");
  options.add("accel_noise_density", sensors.accel_noise_density,
              "IMU accelerometer white noise (m/s^2/sqrt(Hz))");
  options.add("gyro_random_walk", sensors.gyro_random_walk,
              "IMU gyroscope bias random walk (rad/s^2/sqrt(Hz))");
  options.add("accel_random_walk", sensors.accel_random_walk,
              "IMU accelerometer bias random walk (m/s^3/sqrt(Hz))");
  options.add("gyro_range_radps", sensors.gyro_range_radps,
              "IMU gyroscope range (rad/s): rates beyond it are saturated (0: an ADIS16448's)");
  options.add(
      "accel_range_mps2", sensors.accel_range_mps2,
      "IMU accelerometer range (m/s^2): forces beyond it are saturated (0: an ADIS16448's)");
  options.add("T_body_camera", sensors.T_body_camera,
              "camera pose in the body frame, 16 numbers row-major (empty: a Kalibr camchain's "
              "T_cam_imu, else the dataset's cam0/sensor.yaml T_BS, else looking forward)");
  options.add("T_body_imu", sensors.T_body_imu,
              "IMU pose in the body frame, 16 numbers row-major (empty: the dataset's "
              "imu0/sensor.yaml T_BS, else the body frame)");
  options.addFixedSize("p_body_gps_antenna", sensors.p_body_gps_antenna, 3,
                       "GNSS antenna phase centre in the body frame, x y z (m)");
  options.add("gnss_gps_sigma_m", sensors.gnss_errors.gps_sigma_m,
              "GNSS fix sigma per horizontal axis at HDOP 1, autonomous fix (m)");
  options.add("gnss_dgps_sigma_m", sensors.gnss_errors.dgps_sigma_m,
              "GNSS fix sigma per horizontal axis at HDOP 1, DGPS or SBAS fix (m)");
  options.add("gnss_rtk_fixed_sigma_m", sensors.gnss_errors.rtk_fixed_sigma_m,
              "GNSS fix sigma per horizontal axis at HDOP 1, RTK fixed (m)");
  options.add("gnss_rtk_float_sigma_m", sensors.gnss_errors.rtk_float_sigma_m,
              "GNSS fix sigma per horizontal axis at HDOP 1, RTK float (m)");
  options.add("gnss_vertical_ratio", sensors.gnss_errors.vertical_ratio,
              "GNSS fix vertical sigma over horizontal");
  options.add("camera_time_offset_s", sensors.camera_time_offset_s,
              "camera clock minus the IMU's, GNSS's and compass's (s), added to a Kalibr "
              "camchain's");
  options.add("playback_speed", config.playback_speed,
              "replay speed of a timed dataset (1: real time, 0: as fast as possible)");
  options.add("rate_hz", config.rate_hz,
              "frame rate for image folders without stamps (0: as fast as possible)");
  options.add("max_frames", config.max_frames, "stop after this many frames (0: all)");
  options.add("start_at_s", config.start_at_s,
              "replay the dataset from this many seconds in (a restart mid-drive)");
  options.add("min_segment_length_px", config.min_segment_length_px,
              "shortest segment sent (pixels)");
  options.add("min_edge_gradient", config.min_edge_gradient,
              "edge threshold of the line extraction (grey levels per pixel)");
  options.add("min_segment_contrast", config.min_segment_contrast,
              "weakest segment sent (mean grey-level step across it)");
  options.add("corners_on_own_thread", config.corners_on_own_thread,
              "detect each frame's corners on a second thread while its lines are fitted; false "
              "on a one-core robot");
  options.add("domain_id", config.domain_id, "DDS domain id");
  options.add("dds_config", config.dds_config,
              "Cyclone DDS XML configuration file, or several separated by commas, each adding "
              "to the ones before (empty: CYCLONEDDS_URI / defaults)");
  options.add("trajectory_out", config.trajectory_out, "TUM file the received fixes go to");
  options.add("fused_trajectory_out", config.fused_trajectory_out,
              "TUM file of the pose predicted at each frame (what the robot knew then)");
  options.add("fix_log_out", config.fix_log_out,
              "file every PoseFix received goes to: TUM pose, status, counts, covariance (empty: "
              "none)");
  options.add("state_log_out", config.state_log_out,
              "file the camera pose and covariance reported with each RobotState go to: TUM "
              "pose, covariance (empty: none)");
  options.add("state_rate_hz", config.state_rate_hz, "RobotState publication rate");
  options.add("exposure_notices", config.exposure_notices,
              "send each frame's prediction at its exposure, so the backbone removes the hidden "
              "model lines while the robot extracts the image's");
  options.add("realtime_priority", config.realtime_priority,
              "SCHED_FIFO priority (1-99) of the thread that extracts and sends each frame's "
              "lines, so that no other process's thread preempts it on its core (needs "
              "CAP_SYS_NICE or ulimit -r); 0: time-shared");
  options.add("wait_for_backbone_s", config.wait_for_backbone_s,
              "how long to wait for a backbone before sending");
  options.add("fix_timeout_s", config.fix_timeout_s,
              "how long to wait for outstanding answers after the last frame");
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  std::signal(SIGINT, requestStop);
  std::signal(SIGTERM, requestStop);
  lineloc::keepFreedMemoryResident();
  try {
    const lineloc::RobotRunSummary summary = lineloc::runRobot(config, g_stop);
    std::cout << fmt::format(
        "lineloc-robot: {} frames sent ({} held before the navigator had a pose, {} skipped as "
        "their image was missing or corrupt), {} fixes received, {} dropped, {} applied, {} "
        "rejected; exposure -> fix median {:.2f} ms, p99 {:.2f} ms; "
        "with a pose median {:.2f} ms, p99 {:.2f} ms\n"
        "lineloc-robot: LineSet on the wire median {} bytes, p99 {} bytes\n"
        "lineloc-robot: {} states published; {} sensor lines dropped; {}\n",
        summary.frames_sent, summary.frames_before_pose, summary.frames_skipped,
        summary.fixes_received, summary.fixes_dropped, summary.fixes_applied,
        summary.fixes_rejected,
        lineloc::toMilliseconds(lineloc::percentile(summary.latency_ns, 50)),
        lineloc::toMilliseconds(lineloc::percentile(summary.latency_ns, 99)),
        lineloc::toMilliseconds(lineloc::percentile(summary.pose_latency_ns, 50)),
        lineloc::toMilliseconds(lineloc::percentile(summary.pose_latency_ns, 99)),
        lineloc::percentile(summary.line_set_bytes, 50),
        lineloc::percentile(summary.line_set_bytes, 99), summary.states_published,
        summary.sensor_lines_dropped, summary.health);
    std::cout << fmt::format(
        "lineloc-robot: exposure -> fix by stage, ms median/p99/max: front end {}, to the "
        "backbone {}, backbone {}, back {}\n",
        describeLatency(summary.front_end_ns), describeLatency(summary.to_backbone_ns),
        describeLatency(summary.backbone_ns), describeLatency(summary.from_backbone_ns));
    for (const auto& [status, count] : summary.fixes_by_status) {
      std::cout << fmt::format("lineloc-robot:   {:>6} fixes {}\n", count, status);
    }
    return 0;
  } catch (const std::exception& error) {
    spdlog::error("{}", error.what());
    return 1;
  }
}
