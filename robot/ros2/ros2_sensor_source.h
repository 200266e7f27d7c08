// The robot's sensors from ROS 2 topics (ros2_sensor_messages.h), read by
// lineloc-robot as live inputs (robot/input/live_sensors.h): an IMU
// (sensor_msgs/Imu), a GNSS receiver (sensor_msgs/NavSatFix), a camera
// (sensor_msgs/Image, or CompressedImage on a topic whose last token is
// "compressed", as image_transport names it). The readers are best effort,
// so they match the reliable and the best-effort publishers ROS 2's drivers
// use. Their stamps are ROS time, one clock for all of them. A message that
// cannot be taken is dropped, counted and logged (a few lines a second).
#pragma once

#include <atomic>
#include <memory>
#include <string>

#include "common/dds/dds_entities.h"
#include "common/geodesy/site_projection.h"
#include "robot/input/live_sensors.h"

namespace lineloc {

// The ROS 2 topics to read; empty: not read.
struct Ros2SensorTopics {
  std::string imu;
  std::string navsat;
  std::string image;
  // The geoid's height above the WGS84 ellipsoid at the site (m), N in
  // h_msl = h_ellipsoid - N: NavSatFix altitudes are ellipsoidal.
  double geoid_height_m = 0.0;
};

class Ros2SensorSource : public LiveSource {
 public:
  // `site` projects the fixes (nullptr: a NavSatFix topic is refused).
  // Throws std::invalid_argument naming a topic that is not a ROS 2 name.
  Ros2SensorSource(const dds::Participant& participant, const Ros2SensorTopics& topics,
                   std::unique_ptr<SiteProjection> site);
  ~Ros2SensorSource() override;

  void run(const std::function<void(std::vector<LiveReading>)>& arrived,
           const std::atomic<bool>& stop) override;
  bool deliversFrames() const override;
  int64_t dropped() const override { return dropped_; }

 private:
  struct Readers;
  std::unique_ptr<Readers> readers_;
  std::unique_ptr<SiteProjection> site_;
  double geoid_height_m_;
  std::atomic<int64_t> dropped_{0};
  uint32_t next_frame_ = 0;
};

}  // namespace lineloc
