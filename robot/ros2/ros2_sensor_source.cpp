#include "robot/ros2/ros2_sensor_source.h"

#include <fmt/format.h>

#include <optional>
#include <stdexcept>

#include "common/logging/rate_limited_log.h"
#include "robot/ros2/ros2_sensor_messages.h"
#include "robot/ros2/ros2_topics.h"
#include "robot/ros2/ros2_wire.h"

namespace lineloc {
namespace {

// Samples each reader keeps: a camera's frames are taken as they come, and
// an IMU at 400 Hz fills this in a tenth of a second.
constexpr int32_t kHistoryDepth = 64;
// How often run() looks whether it is to stop.
constexpr int64_t kWaitNs = 100'000'000;

template <typename Message>
void openReader(std::optional<dds::Reader<Message>>& reader, const dds::Participant& participant,
                const std::string& ros_topic, const char* option) {
  if (!ros_topic.empty()) {
    reader.emplace(participant, dds::Qos::anyReliability(kHistoryDepth), std::string(),
                   ros2DdsTopic(ros_topic, option));
  }
}

bool compressedTopic(const std::string& ros_topic) {
  return ros_topic.ends_with("/compressed");
}

}  // namespace

struct Ros2SensorSource::Readers {
  std::optional<dds::Reader<sensor_msgs_msg_dds__Imu_>> imu;
  std::optional<dds::Reader<sensor_msgs_msg_dds__NavSatFix_>> navsat;
  std::optional<dds::Reader<sensor_msgs_msg_dds__Image_>> image;
  std::optional<dds::Reader<sensor_msgs_msg_dds__CompressedImage_>> compressed;
  dds::Entity waitset;
};

Ros2SensorSource::Ros2SensorSource(const dds::Participant& participant,
                                   const Ros2SensorTopics& topics,
                                   std::unique_ptr<SiteProjection> site)
    : readers_(std::make_unique<Readers>()),
      site_(std::move(site)),
      geoid_height_m_(topics.geoid_height_m) {
  if (!topics.navsat.empty() && site_ == nullptr) {
    throw std::invalid_argument(
        fmt::format("ros_navsat_topic '{}' needs the site's CRS and origin (site_crs, site_origin)",
                    topics.navsat));
  }
  openReader(readers_->imu, participant, topics.imu, "ros_imu_topic");
  openReader(readers_->navsat, participant, topics.navsat, "ros_navsat_topic");
  if (compressedTopic(topics.image)) {
    openReader(readers_->compressed, participant, topics.image, "ros_image_topic");
  } else {
    openReader(readers_->image, participant, topics.image, "ros_image_topic");
  }
  readers_->waitset = dds::Entity(dds_create_waitset(participant.handle()), "waitset");
  const auto attach = [&](const auto& reader) {
    if (reader) {
      dds::check(dds_waitset_attach(readers_->waitset.handle(), reader->handle(), 0),
                 "waitset attach");
      dds::check(dds_set_status_mask(reader->handle(), DDS_DATA_AVAILABLE_STATUS), "status mask");
    }
  };
  attach(readers_->imu);
  attach(readers_->navsat);
  attach(readers_->image);
  attach(readers_->compressed);
}

Ros2SensorSource::~Ros2SensorSource() = default;

bool Ros2SensorSource::deliversFrames() const {
  return readers_->image.has_value() || readers_->compressed.has_value();
}

void Ros2SensorSource::run(const std::function<void(std::vector<LiveReading>)>& arrived,
                           const std::atomic<bool>& stop) {
  RateLimitedLog dropped_log("dropped ROS 2 messages", 5, 1.0);
  const auto drop = [&](const std::exception& error) {
    ++dropped_;
    dropped_log.log(fmt::format("dropped a ROS 2 message: {}", error.what()));
  };
  while (!stop) {
    dds::check(dds_waitset_wait(readers_->waitset.handle(), nullptr, 0, kWaitNs), "waitset wait");
    std::vector<LiveReading> readings;
    if (readers_->imu) {
      readers_->imu->takeEach([&](const sensor_msgs_msg_dds__Imu_& message) {
        try {
          if (std::optional<ImuSample> sample = imuSampleOf(message)) {
            readings.emplace_back(*sample);
          }
        } catch (const std::runtime_error& error) {
          drop(error);
        }
      });
    }
    if (readers_->navsat) {
      readers_->navsat->takeEach([&](const sensor_msgs_msg_dds__NavSatFix_& message) {
        try {
          if (std::optional<GpsFix> fix = gpsFixOf(message, *site_, geoid_height_m_)) {
            readings.emplace_back(*fix);
          }
        } catch (const std::runtime_error& error) {
          drop(error);
        }
      });
    }
    const auto takeFrame = [&](const auto& message) {
      try {
        CapturedFrame frame;
        frame.image = imageOf(message);
        frame.stamp_ns = stampNs(message.header.stamp);
        readings.emplace_back(LiveFrame{next_frame_++, std::move(frame)});
      } catch (const std::runtime_error& error) {
        drop(error);
      }
    };
    if (readers_->image) {
      readers_->image->takeEach(takeFrame);
    }
    if (readers_->compressed) {
      readers_->compressed->takeEach(takeFrame);
    }
    if (!readings.empty()) {
      arrived(std::move(readings));
    }
  }
}

}  // namespace lineloc
