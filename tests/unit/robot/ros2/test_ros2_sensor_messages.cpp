// What the robot takes from ROS 2 sensor messages, and what it refuses,
// named: encodings it does not take, sizes beyond the pixel limit, rows
// longer than the data, numbers that are not finite, a known covariance that
// is not one; 16-bit and big-endian pixels, BGRA and RGBA as they are.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "robot/ros2/ros2_sensor_messages.h"

namespace lineloc {
namespace {

const SiteProjection& site() {
  static const SiteProjection projection("UTM:31N", Eigen::Vector3d(593000.0, 5763000.0, 0.0));
  return projection;
}

std::string errorOf(const std::function<void()>& take) {
  try {
    take();
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "no error";
}

// A message over `data`, which must outlive it.
sensor_msgs_msg_dds__Image_ image(uint32_t width, uint32_t height, const char* encoding,
                                  uint32_t step, std::vector<uint8_t>& data) {
  sensor_msgs_msg_dds__Image_ message{};
  message.width = width;
  message.height = height;
  message.encoding = const_cast<char*>(encoding);
  message.step = step;
  message.data._buffer = data.data();
  message.data._length = static_cast<uint32_t>(data.size());
  message.data._maximum = message.data._length;
  return message;
}

TEST(Ros2SensorMessages, PixelsOfEveryEncodingItTakes) {
  std::vector<uint8_t> bgra = {10, 20, 30, 255, 40, 50, 60, 0};
  const cv::Mat from_bgra = imageOf(image(2, 1, "bgra8", 8, bgra));
  EXPECT_EQ(from_bgra.type(), CV_8UC3);
  EXPECT_EQ(from_bgra.at<cv::Vec3b>(0, 1), cv::Vec3b(40, 50, 60));
  const cv::Mat from_rgba = imageOf(image(2, 1, "rgba8", 8, bgra));
  EXPECT_EQ(from_rgba.at<cv::Vec3b>(0, 0), cv::Vec3b(30, 20, 10));
  // mono16 little- and big-endian: 0x1234 scaled by 1/256 is 0x12 (18.2 -> 18).
  std::vector<uint8_t> little = {0x34, 0x12, 0x00, 0xFF};
  sensor_msgs_msg_dds__Image_ mono16 = image(2, 1, "mono16", 4, little);
  EXPECT_EQ(imageOf(mono16).at<uint8_t>(0, 0), 0x12);
  EXPECT_EQ(imageOf(mono16).at<uint8_t>(0, 1), 0xFF);
  std::vector<uint8_t> big = {0x12, 0x34, 0xFF, 0x00};
  sensor_msgs_msg_dds__Image_ mono16_big = image(2, 1, "mono16", 4, big);
  mono16_big.is_bigendian = 1;
  EXPECT_EQ(imageOf(mono16_big).at<uint8_t>(0, 0), 0x12);
  // Rows padded beyond their pixels (step > width * bytes per pixel).
  std::vector<uint8_t> padded = {1, 2, 0, 0, 3, 4, 0, 0};
  const cv::Mat mono8 = imageOf(image(2, 2, "mono8", 4, padded));
  EXPECT_EQ(mono8.at<uint8_t>(1, 1), 4);
}

TEST(Ros2SensorMessages, ImagesThatAreNotWhatTheySayAreRefusedNamed) {
  std::vector<uint8_t> data(64, 0);
  EXPECT_NE(
      errorOf([&] { imageOf(image(4, 4, "bayer_rggb8", 4, data)); }).find("encoding 'bayer_rggb8'"),
      std::string::npos);
  EXPECT_NE(errorOf([&] { imageOf(image(0, 4, "mono8", 4, data)); }).find("0 x 4 pixels"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              imageOf(image(100'000, 100'000, "mono8", 100'000, data));
            }).find("beyond 1 to 64000000"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { imageOf(image(4, 4, "bgr8", 4, data)); }).find("step 4"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { imageOf(image(8, 16, "mono8", 8, data)); }).find("64 bytes of data"),
            std::string::npos);
  sensor_msgs_msg_dds__Image_ no_encoding = image(4, 4, "mono8", 4, data);
  no_encoding.encoding = nullptr;
  EXPECT_NE(errorOf([&] { imageOf(no_encoding); }).find("encoding ''"), std::string::npos);
  sensor_msgs_msg_dds__CompressedImage_ garbage{};
  garbage.data._buffer = data.data();
  garbage.data._length = static_cast<uint32_t>(data.size());
  EXPECT_NE(errorOf([&] { imageOf(garbage); }).find("CompressedImage"), std::string::npos);
}

TEST(Ros2SensorMessages, ImuWithoutRatesGivesNothingAndNotFiniteIsRefused) {
  sensor_msgs_msg_dds__Imu_ imu{};
  imu.header.stamp = {12, 500'000'000};
  imu.angular_velocity = {0.1, 0.2, 0.3};
  imu.linear_acceleration = {0.0, 0.0, 9.8};
  const std::optional<ImuSample> sample = imuSampleOf(imu);
  ASSERT_TRUE(sample);
  EXPECT_EQ(sample->stamp_ns, 12'500'000'000);
  imu.linear_acceleration_covariance[0] = -1.0;
  EXPECT_FALSE(imuSampleOf(imu));
  imu.linear_acceleration_covariance[0] = 0.0;
  imu.angular_velocity.z = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(errorOf([&] { imuSampleOf(imu); }).find("not finite"), std::string::npos);
}

TEST(Ros2SensorMessages, FixesTakeTheirCovarianceOrNothingAndBadOnesAreRefused) {
  const GeodeticPosition where = site().toGeodetic({5.0, 6.0, 2.0});
  sensor_msgs_msg_dds__NavSatFix_ fix{};
  fix.latitude = where.latitude_deg;
  fix.longitude = where.longitude_deg;
  fix.altitude = where.height_msl_m + 43.0;
  std::optional<GpsFix> taken = gpsFixOf(fix, site(), 43.0);
  ASSERT_TRUE(taken);
  EXPECT_LT((taken->p_world_antenna - Eigen::Vector3d(5.0, 6.0, 2.0)).norm(), 1e-6);
  EXPECT_EQ(taken->horizontal_sigma_m, 0.0);  // unknown: the navigator's
  fix.position_covariance_type = 1;
  const double known[9] = {2.0, 0, 0, 0, 8.0, 0, 0, 0, 18.0};
  std::copy(known, known + 9, fix.position_covariance);
  taken = gpsFixOf(fix, site(), 43.0);
  EXPECT_DOUBLE_EQ(taken->horizontal_sigma_m, std::sqrt(8.0));
  EXPECT_DOUBLE_EQ(taken->vertical_sigma_m, std::sqrt(18.0));
  fix.position_covariance[4] = -1.0;
  EXPECT_NE(errorOf([&] { gpsFixOf(fix, site(), 43.0); }).find("not positive and finite"),
            std::string::npos);
  fix.status.status = -1;
  EXPECT_FALSE(gpsFixOf(fix, site(), 43.0));
  fix.status.status = 0;
  fix.latitude = std::numeric_limits<double>::infinity();
  EXPECT_NE(errorOf([&] { gpsFixOf(fix, site(), 43.0); }).find("not finite"), std::string::npos);
}

}  // namespace
}  // namespace lineloc
