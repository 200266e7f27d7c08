// What the robot takes from ROS 2's sensor messages (common_interfaces'
// sensor_msgs), each checked as input from outside:
//  - Imu: the rates and the specific force in the IMU's frame, as a sample of
//    imu0/data.csv; a message that says it has no rates or no acceleration
//    (covariance[0] = -1, the message's convention) gives none;
//  - NavSatFix: a fix in the site frame. Its altitude is above the WGS84
//    ellipsoid, the site's heights above mean sea level: h_msl = altitude -
//    N, N the geoid's height at the site. Its sigmas are the covariance's
//    (ENU, m^2: per horizontal axis the larger of east and north) where the
//    message knows it (position_covariance_type 1-3), else the navigator's;
//    a message without a fix (status -1) gives none;
//  - Image: mono8, mono16, bgr8, rgb8, bgra8 and rgba8 pixels, as an 8-bit
//    grey or BGR cv::Mat (16 bits scaled by 1/256); CompressedImage: a JPEG or
//    PNG, decoded within the robot's pixel limit (common/image/image_file.h).
// Each is stamped with its header's time, the publisher's clock.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "common/geodesy/site_projection.h"
#include "robot/inertial/imu_sample.h"
#include "robot/inertial/navigator_measurements.h"
#include "ros2.h"

namespace lineloc {

// nullopt for a message without rates or acceleration; throws
// std::runtime_error for one whose numbers are not finite.
std::optional<ImuSample> imuSampleOf(const sensor_msgs_msg_dds__Imu_& message);

// nullopt for a message without a fix; throws std::runtime_error for one
// whose position or covariance is not finite, or outside the site's CRS.
std::optional<GpsFix> gpsFixOf(const sensor_msgs_msg_dds__NavSatFix_& message,
                               const SiteProjection& site, double geoid_height_m);

// Throws std::runtime_error naming what is wrong: an encoding it does not
// take, a size beyond the pixel limit, a row step shorter than a row or data
// shorter than its rows, an image that does not decode.
cv::Mat imageOf(const sensor_msgs_msg_dds__Image_& message);
cv::Mat imageOf(const sensor_msgs_msg_dds__CompressedImage_& message);

}  // namespace lineloc
