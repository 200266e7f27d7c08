// The robot's side of the loop: for each camera frame, extract segments and
// publish a LineSet with the predicted pose; take the backbone's PoseFix
// answers, check them, and write them as a TUM trajectory.
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/geometry/pose.h"

namespace lineloc {

struct RobotConfig {
  std::string robot_id = "robot1";
  std::string images;
  std::string calibration;
  // Predicted T_world_camera: tx ty tz qx qy qz qw (site frame, metres).
  std::vector<double> predicted_pose = {0.0, 0.0, 1.5, 0.0, 0.0, 0.0, 1.0};
  double predicted_position_sigma_m = 5.0;
  double predicted_rotation_sigma_deg = 10.0;
  double rate_hz = 10.0;
  int max_frames = 0;
  double min_segment_length_px = 20.0;
  int domain_id = 0;
  std::string dds_config;
  std::string trajectory_out = "poses.tum";
  double wait_for_backbone_s = 5.0;
  double fix_timeout_s = 2.0;
};

struct RobotRunSummary {
  int frames_sent = 0;
  int fixes_received = 0;
  int fixes_dropped = 0;
  std::map<std::string, int> fixes_by_status;
  // Publish -> PoseFix received on this robot, per answered frame.
  std::vector<int64_t> round_trip_ns;
};

// Runs the image sequence through the loop. Stops early when `stop` becomes
// true. Throws std::runtime_error on bad configuration or unreadable input;
// a missing or vanished backbone is not an error (frames go unanswered).
RobotRunSummary runRobot(const RobotConfig& config, const std::atomic<bool>& stop);

// Nearest-rank percentile (0..100) of `values`; 0 for an empty list.
int64_t percentile(std::vector<int64_t> values, double percent);

}  // namespace lineloc
