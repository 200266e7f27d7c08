// lineloc-robot: the onboard agent. Reads camera frames, sends their line
// segments to the backbone over DDS and writes the poses it gets back.
#include <spdlog/spdlog.h>

#include <atomic>
#include <csignal>
#include <iostream>

#include "common/config/program_options.h"
#include "robot/agent/robot_agent.h"

namespace {
std::atomic<bool> g_stop{false};
void requestStop(int) { g_stop = true; }
}  // namespace

int main(int argc, char** argv) {
  lineloc::RobotConfig config;
  lineloc::ProgramOptions options("lineloc-robot", "lineloc onboard agent");
  options.add("robot_id", config.robot_id, "this robot's id, [A-Za-z0-9][A-Za-z0-9_.-]*");
  options.add("images", config.images, "image folder, EuRoC/ASL dataset or cam0/ folder");
  options.add("calibration", config.calibration, "camera calibration (OpenCV YAML layout)");
  options.add("predicted_pose", config.predicted_pose,
              "predicted T_world_camera: tx ty tz qx qy qz qw");
  options.add("predicted_position_sigma_m", config.predicted_position_sigma_m,
              "standard deviation of the predicted position (m)");
  options.add("predicted_rotation_sigma_deg", config.predicted_rotation_sigma_deg,
              "standard deviation of the predicted rotation (degrees)");
  options.add("rate_hz", config.rate_hz, "frames per second to send (0: as fast as possible)");
  options.add("max_frames", config.max_frames, "stop after this many frames (0: all)");
  options.add("min_segment_length_px", config.min_segment_length_px,
              "shortest segment sent (pixels)");
  options.add("domain_id", config.domain_id, "DDS domain id");
  options.add("dds_config", config.dds_config,
              "Cyclone DDS XML configuration file (empty: CYCLONEDDS_URI / defaults)");
  options.add("trajectory_out", config.trajectory_out, "TUM file the received poses go to");
  options.add("wait_for_backbone_s", config.wait_for_backbone_s,
              "how long to wait for a backbone before sending");
  options.add("fix_timeout_s", config.fix_timeout_s,
              "how long to wait for outstanding answers after the last frame");
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  std::signal(SIGINT, requestStop);
  std::signal(SIGTERM, requestStop);
  try {
    const lineloc::RobotRunSummary summary = lineloc::runRobot(config, g_stop);
    std::cout << fmt::format(
        "lineloc-robot: {} frames sent, {} fixes received, {} dropped; round trip median "
        "{:.2f} ms, p99 {:.2f} ms\n",
        summary.frames_sent, summary.fixes_received, summary.fixes_dropped,
        lineloc::percentile(summary.round_trip_ns, 50) * 1e-6,
        lineloc::percentile(summary.round_trip_ns, 99) * 1e-6);
    for (const auto& [status, count] : summary.fixes_by_status) {
      std::cout << fmt::format("lineloc-robot:   {:>6} fixes {}\n", count, status);
    }
    return 0;
  } catch (const std::exception& error) {
    spdlog::error("{}", error.what());
    return 1;
  }
}
