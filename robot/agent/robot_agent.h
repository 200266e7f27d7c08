// The robot's side of the loop (paper §1.2): its camera, IMU, DGPS and
// compass, replayed from a dataset as they were measured or read live
// (robot/input/live_sensors.h), go through the robot's loop
// (robot_loop.h): the inertial navigator (robot/inertial) started from DGPS
// and compass keeps the pose; each camera frame sends the pose predicted at
// its exposure, then its segments and corners; each PoseFix that comes back
// is applied at its frame's time.
//
// Without IMU data (a plain image folder, a live camera alone) the
// prediction is the configured pose, and the loop only exercises the link.
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/geometry/pose.h"
#include "robot/agent/sensor_setup.h"
#include "robot/input/live_sensors.h"
#include "robot/ros2/ros2_sensor_source.h"
#include "robot/ros2/ros2_state_publisher.h"
#include "robot/vision/features/feature_extractor.h"

namespace lineloc {

struct RobotConfig {
  std::string robot_id = "robot1";
  // A dataset replayed: EuRoC/ASL folder, cam0/ folder or folder of images.
  std::string images;
  // Live sensors instead (camera_source set): camera, GNSS and IMU sources.
  LiveSensorConfig live;
  // ROS 2 (robot/ros2): the domain it speaks on (-1: none), its Cyclone DDS
  // configuration files, the topics the robot's state goes to and the
  // sensors' topics it reads (live, as the sources above: an image topic
  // stands for camera_source).
  int ros_domain_id = -1;
  std::string ros_dds_config;
  Ros2StateTopics ros_state;
  Ros2SensorTopics ros_sensors;
  std::string camera_calibration;
  // Without IMU data: the predicted T_world_camera, tx ty tz qx qy qz qw (site frame).
  std::vector<double> predicted_pose = {0.0, 0.0, 1.5, 0.0, 0.0, 0.0, 1.0};
  double predicted_position_sigma_m = 5.0;
  double predicted_rotation_sigma_deg = 10.0;
  // With IMU data and no GNSS: T_world_camera where the robot stands when it
  // starts, tx ty tz qx qy qz qw (site frame), with these sigmas; empty:
  // none, and the robot starts from DGPS and compass.
  std::vector<double> start_pose;
  double start_position_sigma_m = 0.5;
  double start_rotation_sigma_deg = 5.0;
  // Height of the camera above the ground under the robot (m); 0: unknown.
  double camera_height_m = 0.0;
  // Site frame for DGPS: CRS ("EPSG:7415") and origin (x y z) subtracted from it.
  std::string site_crs;
  std::vector<double> site_origin = {0.0, 0.0, 0.0};
  double magnetic_declination_deg = 0.0;
  // The IMU's noise and range, the sensors' mounting, the camera clock's offset.
  SensorSetup sensors;
  // Replay speed for timed datasets (1: real time; 0: as fast as possible).
  double playback_speed = 1.0;
  // Frame rate for image folders without time stamps (0: as fast as possible).
  double rate_hz = 10.0;
  int max_frames = 0;
  // Replay a dataset from this many seconds in, as a robot whose software
  // restarts mid-drive: its navigator sees nothing before.
  double start_at_s = 0.0;
  double min_segment_length_px = 20.0;
  // The front end's floor of the edge threshold (grey levels per pixel; the
  // threshold rises with each frame's estimated noise, EdgeDetectorOptions)
  // and of the weakest segment it sends (mean grey-level step across it; 0:
  // each segment is validated against the frame's noise alone,
  // SegmentValidation). A step of h grey levels, blurred by the 1 px
  // smoothing, peaks at a gradient of 0.34 h: the floor of 4 keeps the steps
  // of 12 grey levels and over, where walls in shade meet each other and the
  // shaded street. The backbone's searches take only the segments of 20 grey
  // levels and over (AcquisitionOptions::min_segment_contrast); tracking takes
  // every one.
  double min_edge_gradient = trackingFrontEndOptions().edges.min_gradient;
  double min_segment_contrast = trackingFrontEndOptions().lines.min_contrast;
  // Detect each frame's corners on a second thread while its lines are linked
  // and fitted (FeatureExtractorOptions::corners_on_own_thread); off on a
  // one-core robot, where that thread only shares the core.
  bool corners_on_own_thread = true;
  int domain_id = 0;
  std::string dds_config;
  std::string trajectory_out = "poses.tum";
  std::string fused_trajectory_out = "fused.tum";
  // Every PoseFix received, with its status and covariance (fix_log.h); empty: none.
  std::string fix_log_out;
  // The camera pose and covariance the robot reports with each RobotState it
  // publishes (pose_covariance_log.h); empty: none.
  std::string state_log_out;
  double state_rate_hz = 20.0;
  // Send each frame's prediction at its exposure, before its lines
  // (ExposureTopic): the backbone then removes the hidden model lines while
  // the robot extracts the image's.
  bool exposure_notices = true;
  // SCHED_FIFO priority (1-99) of the thread that extracts each frame's lines
  // and sends them (thread_priority.h); 0: time-shared like the rest. A
  // refusal is logged and the robot runs time-shared, as it does when
  // replaying as fast as possible.
  int realtime_priority = 0;
  double wait_for_backbone_s = 5.0;
  double fix_timeout_s = 2.0;
};

struct RobotRunSummary {
  int frames_sent = 0;
  // Frames held, not sent, before the navigator had a pose: standing still
  // for its alignment, then DGPS or a vision fix for its position.
  int frames_before_pose = 0;
  // Frames skipped as their image was missing or could not be decoded.
  int frames_skipped = 0;
  int fixes_received = 0;
  int fixes_dropped = 0;
  int fixes_applied = 0;
  int fixes_rejected = 0;
  int states_published = 0;
  int sensor_lines_dropped = 0;
  std::map<std::string, int> fixes_by_status;
  // Frame exposure -> PoseFix received, per answered frame, and for the
  // answers that carried a pose (FIX_OK).
  std::vector<int64_t> latency_ns;
  std::vector<int64_t> pose_latency_ns;
  // latency_ns split, per answered frame, at the clock readings the robot
  // and the backbone take: exposure -> LineSet handed to DDS (the robot's
  // front end); from there to the PoseFix's write, less the backbone's own
  // time (DDS to the backbone, the LineSet waiting to be taken, and the
  // answer's hand-over to DDS); the backbone's own time (the PoseFix's
  // timings.total); and the PoseFix's write -> taken by the robot (DDS back,
  // and the answer waiting between the robot's other work). The write is
  // stamped on the backbone's clock (dds::SampleInfo), so the two DDS legs
  // are only as good as the hosts' clock synchronisation; their sum is exact.
  // The backbone can start on a LineSet before the write that sent it has
  // returned, so the front end ends before the write.
  std::vector<int64_t> front_end_ns;
  std::vector<int64_t> to_backbone_ns;
  std::vector<int64_t> backbone_ns;
  std::vector<int64_t> from_backbone_ns;
  // Each LineSet's bytes on the wire (dds::serializedSizeBytes), per frame sent.
  std::vector<int64_t> line_set_bytes;
  std::string health;
};

// The options of the robot's line and corner extraction under `config`.
FeatureExtractorOptions frontEndOptions(const RobotConfig& config);

// Runs the input through the loop. Stops early when `stop` becomes true.
// Throws std::runtime_error on bad configuration, unreadable input or a
// dataset without the sensors the robot needs (requireNavigationSensors,
// sensor_streams.h); a frame whose image is missing or corrupt is skipped,
// counted and logged (at most a few lines a second), and a missing or
// vanished backbone is not an error (the robot dead-reckons).
RobotRunSummary runRobot(const RobotConfig& config, const std::atomic<bool>& stop);

}  // namespace lineloc
