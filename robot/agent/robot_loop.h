// What the robot does with each input, replayed from a dataset or live: IMU,
// DGPS and compass go to the inertial navigator; a camera frame gets the pose
// the navigator predicts at its exposure, sent at once (ExposureTopic,
// common/messages/topics.h), then its segments and corners, extracted by the
// front end; each PoseFix that comes back (late) is applied at its frame's
// time; the fused state (RobotState, and for ROS 2 base_link's pose,
// odometry and transform, ros2_state_publisher.h) is published at a fixed
// rate. Without a
// navigator (no IMU) every frame carries the configured prediction.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>

#include "common/camera/camera_calibration.h"
#include "common/messages/messages.h"
#include "robot/agent/robot_agent.h"
#include "robot/inertial/inertial_navigator.h"

namespace lineloc {

class RobotLoop {
 public:
  // `navigator` (null: none) and `ros` (null: none), where the fused state is
  // published for ROS 2 too, outlive the loop. Joins the DDS domain.
  RobotLoop(const RobotConfig& config, const CameraCalibration& calibration,
            InertialNavigator* navigator, const dds::Participant* ros, RobotRunSummary& summary);
  ~RobotLoop();
  RobotLoop(const RobotLoop&) = delete;
  RobotLoop& operator=(const RobotLoop&) = delete;

  // Waits up to wait_for_backbone_s for a backbone to answer LineSets.
  void waitForBackbone(const std::atomic<bool>& stop);

  void addImu(const ImuSample& sample);
  void addGps(const GpsFix& fix);
  void addGpsVelocity(const GpsVelocity& velocity);
  void addCompass(const CompassReading& reading);

  // The LineSet of frame `sequence_number` exposed at `stamp_ns`, with the
  // pose predicted then, sent at once as an exposure notice; nullopt, the
  // frame counted as held, while the navigator has no pose yet.
  std::optional<LineSetData> expose(uint32_t sequence_number, int64_t stamp_ns);
  // Extracts the image's segments and corners into `line_set` and sends it;
  // `exposure_steady_ns` is when it was exposed, on the steady clock.
  void send(LineSetData& line_set, const cv::Mat& image, int64_t exposure_steady_ns);

  // Takes the answers that come within `timeout_ns`.
  void poll(int64_t timeout_ns);
  bool answered(uint32_t sequence_number) const;
  // Publishes the fused state when it is due.
  void publishStateIfDue();
  // Waits up to fix_timeout_s for the answers still outstanding.
  void finish(const std::atomic<bool>& stop);

 private:
  struct Links;
  const RobotConfig& config_;
  const CameraCalibration& calibration_;
  InertialNavigator* navigator_;
  RobotRunSummary& summary_;
  PoseWithCovariance configured_;
  std::unique_ptr<Links> links_;
  std::unique_ptr<Ros2StatePublisher> ros_;
  int64_t next_state_ns_ = 0;
};

}  // namespace lineloc
