// Feeds arbitrary bytes to the robot's readers of ROS 2 sensor messages as
// DDS delivers them: the first byte picks the type (Imu, NavSatFix, Image,
// CompressedImage), the rest is its CDR body, which Cyclone DDS checks
// against the type and reads as it reads what arrives; whatever it accepts,
// ros2_sensor_messages.h must take or refuse with a std::runtime_error.
#include <dds/ddsi/ddsi_cdrstream.h>
#include <dds/ddsi/q_protocol.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "robot/ros2/ros2_sensor_messages.h"

namespace {

template <typename Message, typename Take>
void deliver(const dds_topic_descriptor_t& type, const uint8_t* data, size_t size, Take take) {
  if (size == 0) {
    return;  // no sample is empty
  }
  std::vector<char> body(data, data + size);
  uint32_t offset = 0;
  if (dds_stream_normalize_data(body.data(), &offset, static_cast<uint32_t>(body.size()), false,
                                CDR_ENC_VERSION_1, type.m_ops) == nullptr) {
    return;  // Cyclone drops what is not a sample of the type
  }
  std::vector<char> sample(type.m_size, 0);
  dds_istream_t stream;
  dds_istream_init(&stream, static_cast<uint32_t>(body.size()), body.data(), CDR_ENC_VERSION_1);
  dds_stream_read(&stream, sample.data(), type.m_ops);
  dds_istream_fini(&stream);
  try {
    take(*reinterpret_cast<const Message*>(sample.data()));
  } catch (const std::runtime_error&) {
    // refused, named
  }
  dds_stream_free_sample(sample.data(), type.m_ops);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) {
    return 0;
  }
  static const lineloc::SiteProjection site("UTM:31N", Eigen::Vector3d(593000.0, 5763000.0, 0.0));
  switch (data[0] % 4) {
    case 0:
      deliver<sensor_msgs_msg_dds__Imu_>(sensor_msgs_msg_dds__Imu__desc, data + 1, size - 1,
                                         [](const auto& m) { lineloc::imuSampleOf(m); });
      break;
    case 1:
      deliver<sensor_msgs_msg_dds__NavSatFix_>(
          sensor_msgs_msg_dds__NavSatFix__desc, data + 1, size - 1,
          [](const auto& m) { lineloc::gpsFixOf(m, site, 43.0); });
      break;
    case 2:
      deliver<sensor_msgs_msg_dds__Image_>(sensor_msgs_msg_dds__Image__desc, data + 1, size - 1,
                                           [](const auto& m) { lineloc::imageOf(m); });
      break;
    default:
      deliver<sensor_msgs_msg_dds__CompressedImage_>(sensor_msgs_msg_dds__CompressedImage__desc,
                                                     data + 1, size - 1,
                                                     [](const auto& m) { lineloc::imageOf(m); });
      break;
  }
  return 0;
}
