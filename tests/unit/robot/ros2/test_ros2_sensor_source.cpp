// Ros2SensorSource: ROS 2 sensor messages encoded by an implementation of
// ROS 2's CDR independent of lineloc's (Foxglove's, ROS 2 Humble's
// definitions), put on ROS 2's topics, come to the robot as what they say:
// an IMU sample, a DGPS fix in the site frame with the covariance's sigmas,
// camera frames from raw and compressed images; messages it cannot take are
// dropped and counted, and the source goes on.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "robot/ros2/ros2_sensor_source.h"
#include "robot/ros2/ros2_topics.h"
#include "tests/support/foxglove_cdr.h"
#include "tests/support/serialized_samples.h"
#include "tests/support/test_dds.h"

namespace lineloc {
namespace {

using test::encodedByFoxglove;

const Eigen::Vector3d kSiteOrigin(593000.0, 5763000.0, 0.0);
constexpr double kGeoidHeightM = 43.0;
constexpr int64_t kStampNs = 1'776'159'012'250'000'000;

nlohmann::json header(const std::string& frame) {
  return {{"stamp", {{"sec", kStampNs / 1'000'000'000}, {"nanosec", kStampNs % 1'000'000'000}}},
          {"frame_id", frame}};
}

std::vector<double> covariance3(double xx, double yy, double zz) {
  return {xx, 0, 0, 0, yy, 0, 0, 0, zz};
}

// RFC 4648 base64, as ros2_cdr.js takes byte arrays.
std::string base64(const std::vector<uint8_t>& bytes) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t chunk = static_cast<uint32_t>(bytes[i]) << 16;
    if (n > 1) {
      chunk |= static_cast<uint32_t>(bytes[i + 1]) << 8;
    }
    if (n > 2) {
      chunk |= bytes[i + 2];
    }
    for (size_t k = 0; k < 4; ++k) {
      text += k <= n ? kDigits[(chunk >> (18 - 6 * k)) & 63] : '=';
    }
  }
  return text;
}

// A 64 x 48 test card: a grey ramp, a red square.
cv::Mat testCard() {
  cv::Mat image(48, 64, CV_8UC3);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const auto grey = static_cast<uchar>(3 * x + y);
      image.at<cv::Vec3b>(y, x) = cv::Vec3b(grey, grey, grey);
    }
  }
  image(cv::Rect(10, 10, 12, 12)).setTo(cv::Scalar(0, 0, 255));
  return image;
}

class Ros2SensorSourceTest : public ::testing::Test {
 protected:
  // Runs the source until `expected` readings came or a few seconds passed.
  std::vector<LiveReading> readingsOf(Ros2SensorSource& source, size_t expected,
                                      const std::function<void()>& publish) {
    std::vector<LiveReading> readings;
    std::mutex mutex;
    std::atomic<bool> stop{false};
    std::thread runner([&] {
      source.run(
          [&](std::vector<LiveReading> arrived) {
            std::lock_guard lock(mutex);
            for (LiveReading& reading : arrived) {
              readings.push_back(std::move(reading));
            }
          },
          stop);
    });
    publish();
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (std::chrono::steady_clock::now() < deadline) {
      {
        std::lock_guard lock(mutex);
        if (readings.size() >= expected) {
          break;
        }
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    stop = true;
    runner.join();
    return readings;
  }

  dds::Domain domain_{test::testDomainId(), test::testDdsConfig()};
  dds::Participant participant_{domain_};
};

TEST_F(Ros2SensorSourceTest, TakesImuFixAndFramesAsTheMessagesSayThem) {
  Ros2SensorTopics topics;
  topics.imu = "/imu/data";
  topics.navsat = "/gnss/fix";
  topics.image = "/camera/image_raw";
  topics.geoid_height_m = kGeoidHeightM;
  Ros2SensorSource source(participant_, topics,
                          std::make_unique<SiteProjection>("UTM:31N", kSiteOrigin));
  EXPECT_TRUE(source.deliversFrames());
  test::SerializedWriter imu(participant_, sensor_msgs_msg_dds__Imu__desc, "rt/imu/data");
  test::SerializedWriter navsat(participant_, sensor_msgs_msg_dds__NavSatFix__desc, "rt/gnss/fix");
  test::SerializedWriter image(participant_, sensor_msgs_msg_dds__Image__desc,
                               "rt/camera/image_raw");

  const std::vector<double> none(9, 0.0);
  const std::vector<uint8_t> imu_bytes = encodedByFoxglove(
      "sensor_msgs/Imu",
      {{"header", header("imu_link")},
       {"orientation", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}, {"w", 1.0}}},
       {"orientation_covariance", std::vector<double>{-1, 0, 0, 0, 0, 0, 0, 0, 0}},
       {"angular_velocity", {{"x", 0.01}, {"y", -0.02}, {"z", 0.25}}},
       {"angular_velocity_covariance", none},
       {"linear_acceleration", {{"x", 0.3}, {"y", 0.1}, {"z", 9.81}}},
       {"linear_acceleration_covariance", none}});
  const SiteProjection site("UTM:31N", kSiteOrigin);
  const Eigen::Vector3d p_site(25.0, -12.0, 3.0);
  const GeodeticPosition where = site.toGeodetic(p_site);
  const std::vector<uint8_t> fix_bytes = encodedByFoxglove(
      "sensor_msgs/NavSatFix", {{"header", header("gnss")},
                                {"status", {{"status", 1}, {"service", 1}}},
                                {"latitude", where.latitude_deg},
                                {"longitude", where.longitude_deg},
                                {"altitude", where.height_msl_m + kGeoidHeightM},
                                {"position_covariance", covariance3(4.0, 9.0, 36.0)},
                                {"position_covariance_type", 2}});
  const cv::Mat card = testCard();
  cv::Mat rgb;
  cv::cvtColor(card, rgb, cv::COLOR_BGR2RGB);
  const std::vector<uint8_t> pixels(rgb.datastart, rgb.dataend);
  const std::vector<uint8_t> image_bytes =
      encodedByFoxglove("sensor_msgs/Image", {{"header", header("camera")},
                                              {"height", 48},
                                              {"width", 64},
                                              {"encoding", "rgb8"},
                                              {"is_bigendian", 0},
                                              {"step", 64 * 3},
                                              {"data", {{"base64", base64(pixels)}}}});
  // A frame whose rows are longer than its data: dropped, counted.
  nlohmann::json short_image = nlohmann::json{{"header", header("camera")},
                                              {"height", 480},
                                              {"width", 640},
                                              {"encoding", "mono8"},
                                              {"is_bigendian", 0},
                                              {"step", 640},
                                              {"data", {{"base64", base64(pixels)}}}};
  const std::vector<uint8_t> short_bytes = encodedByFoxglove("sensor_msgs/Image", short_image);

  const std::vector<LiveReading> readings = readingsOf(source, 3, [&] {
    image.write(short_bytes);
    imu.write(imu_bytes);
    navsat.write(fix_bytes);
    image.write(image_bytes);
  });
  ASSERT_EQ(readings.size(), 3u);
  int seen = 0;
  for (const LiveReading& reading : readings) {
    if (const auto* sample = std::get_if<ImuSample>(&reading)) {
      ++seen;
      EXPECT_EQ(sample->stamp_ns, kStampNs);
      EXPECT_EQ(sample->gyro_radps, Eigen::Vector3d(0.01, -0.02, 0.25));
      EXPECT_EQ(sample->accel_mps2, Eigen::Vector3d(0.3, 0.1, 9.81));
    } else if (const auto* fix = std::get_if<GpsFix>(&reading)) {
      ++seen;
      EXPECT_EQ(fix->stamp_ns, kStampNs);
      EXPECT_LT((fix->p_world_antenna - p_site).norm(), 1e-6);
      EXPECT_DOUBLE_EQ(fix->horizontal_sigma_m, 3.0);
      EXPECT_DOUBLE_EQ(fix->vertical_sigma_m, 6.0);
    } else if (const auto* frame = std::get_if<LiveFrame>(&reading)) {
      ++seen;
      EXPECT_EQ(frame->captured.stamp_ns, kStampNs);
      EXPECT_EQ(cv::norm(frame->captured.image, card, cv::NORM_INF), 0.0);
    }
  }
  EXPECT_EQ(seen, 3);
  EXPECT_EQ(source.dropped(), 1);
}

TEST_F(Ros2SensorSourceTest, ACompressedImageIsDecoded) {
  Ros2SensorTopics topics;
  topics.image = "/camera/image_raw/compressed";
  Ros2SensorSource source(participant_, topics, nullptr);
  test::SerializedWriter writer(participant_, sensor_msgs_msg_dds__CompressedImage__desc,
                                "rt/camera/image_raw/compressed");
  std::vector<uint8_t> png;
  ASSERT_TRUE(cv::imencode(".png", testCard(), png));
  const std::vector<uint8_t> bytes = encodedByFoxglove(
      "sensor_msgs/CompressedImage",
      {{"header", header("camera")}, {"format", "png"}, {"data", {{"base64", base64(png)}}}});
  const std::vector<LiveReading> readings = readingsOf(source, 1, [&] { writer.write(bytes); });
  ASSERT_EQ(readings.size(), 1u);
  const auto* frame = std::get_if<LiveFrame>(&readings[0]);
  ASSERT_NE(frame, nullptr);
  EXPECT_EQ(cv::norm(frame->captured.image, testCard(), cv::NORM_INF), 0.0);
}

TEST_F(Ros2SensorSourceTest, AFixTopicWithoutASiteAndABadTopicNameAreRefusedNamed) {
  Ros2SensorTopics topics;
  topics.navsat = "/fix";
  try {
    Ros2SensorSource source(participant_, topics, nullptr);
    FAIL() << "fixes without a site frame";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("ros_navsat_topic '/fix'"), std::string::npos);
  }
  topics.navsat.clear();
  topics.imu = "/imu//data";
  EXPECT_THROW(Ros2SensorSource(participant_, topics, nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
