#include "robot/ros2/ros2_sensor_messages.h"

#include <fmt/format.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "common/image/image_file.h"
#include "robot/ros2/ros2_wire.h"

namespace lineloc {
namespace {

// sensor_msgs/NavSatStatus STATUS_NO_FIX; NavSatFix COVARIANCE_TYPE_UNKNOWN.
constexpr int kNoFix = -1;
constexpr int kCovarianceUnknown = 0;

Eigen::Vector3d vectorOf(const geometry_msgs_msg_dds__Vector3_& v) {
  return {v.x, v.y, v.z};
}

struct PixelFormat {
  const char* encoding;
  int type;
  int to_bgr;  // cv::cvtColor code, or -1: none
};

constexpr PixelFormat kPixelFormats[] = {
    {"mono8", CV_8UC1, -1},
    {"mono16", CV_16UC1, -1},
    {"bgr8", CV_8UC3, -1},
    {"rgb8", CV_8UC3, cv::COLOR_RGB2BGR},
    {"bgra8", CV_8UC4, cv::COLOR_BGRA2BGR},
    {"rgba8", CV_8UC4, cv::COLOR_RGBA2BGR},
};

}  // namespace

std::optional<ImuSample> imuSampleOf(const sensor_msgs_msg_dds__Imu_& message) {
  if (message.angular_velocity_covariance[0] == -1.0 ||
      message.linear_acceleration_covariance[0] == -1.0) {
    return std::nullopt;
  }
  ImuSample sample{stampNs(message.header.stamp), vectorOf(message.angular_velocity),
                   vectorOf(message.linear_acceleration)};
  if (!sample.gyro_radps.allFinite() || !sample.accel_mps2.allFinite()) {
    throw std::runtime_error("Imu: rates or acceleration not finite");
  }
  return sample;
}

std::optional<GpsFix> gpsFixOf(const sensor_msgs_msg_dds__NavSatFix_& message,
                               const SiteProjection& site, double geoid_height_m) {
  if (message.status.status <= kNoFix) {
    return std::nullopt;
  }
  if (!std::isfinite(message.latitude) || !std::isfinite(message.longitude) ||
      !std::isfinite(message.altitude)) {
    throw std::runtime_error("NavSatFix: position not finite");
  }
  GpsFix fix;
  fix.stamp_ns = stampNs(message.header.stamp);
  try {
    fix.p_world_antenna =
        site.toSite({message.latitude, message.longitude, message.altitude - geoid_height_m});
  } catch (const std::domain_error&) {
    throw std::runtime_error(fmt::format("NavSatFix: {:.7f}, {:.7f} is outside the site's CRS",
                                         message.latitude, message.longitude));
  }
  if (message.position_covariance_type != kCovarianceUnknown) {
    const double* c = message.position_covariance;
    if (!(c[0] > 0.0 && c[4] > 0.0 && c[8] > 0.0 && std::isfinite(c[0]) && std::isfinite(c[4]) &&
          std::isfinite(c[8]))) {
      throw std::runtime_error("NavSatFix: a known covariance that is not positive and finite");
    }
    fix.horizontal_sigma_m = std::sqrt(std::max(c[0], c[4]));
    fix.vertical_sigma_m = std::sqrt(c[8]);
  }
  return fix;
}

cv::Mat imageOf(const sensor_msgs_msg_dds__Image_& message) {
  const std::string encoding = message.encoding != nullptr ? message.encoding : "";
  const PixelFormat* format = nullptr;
  for (const PixelFormat& candidate : kPixelFormats) {
    if (encoding == candidate.encoding) {
      format = &candidate;
    }
  }
  if (format == nullptr) {
    throw std::runtime_error(fmt::format(
        "Image: encoding '{}' is not one of mono8, mono16, bgr8, rgb8, bgra8, rgba8", encoding));
  }
  const int64_t width = message.width;
  const int64_t height = message.height;
  if (width == 0 || height == 0 || width * height > kDefaultMaxImagePixels) {
    throw std::runtime_error(fmt::format("Image: {} x {} pixels, beyond 1 to {}", width, height,
                                         kDefaultMaxImagePixels));
  }
  const int64_t row_bytes = width * static_cast<int64_t>(CV_ELEM_SIZE(format->type));
  if (message.step < row_bytes ||
      static_cast<int64_t>(message.data._length) < static_cast<int64_t>(message.step) * height) {
    throw std::runtime_error(
        fmt::format("Image: step {} and {} bytes of data for {} rows of {} bytes", message.step,
                    message.data._length, height, row_bytes));
  }
  const cv::Mat view(static_cast<int>(height), static_cast<int>(width), format->type,
                     message.data._buffer, message.step);
  cv::Mat image;
  if (format->type == CV_16UC1) {
    cv::Mat pixels = view.clone();
    if (message.is_bigendian != 0) {
      pixels.forEach<uint16_t>([](uint16_t& value, const int*) {
        value = static_cast<uint16_t>((value >> 8) | (value << 8));
      });
    }
    pixels.convertTo(image, CV_8UC1, 1.0 / 256.0);
  } else if (format->to_bgr >= 0) {
    cv::cvtColor(view, image, format->to_bgr);
  } else {
    image = view.clone();
  }
  return image;
}

cv::Mat imageOf(const sensor_msgs_msg_dds__CompressedImage_& message) {
  return decodeImageBytes(message.data._buffer, message.data._length, cv::IMREAD_COLOR,
                          "CompressedImage");
}

}  // namespace lineloc
