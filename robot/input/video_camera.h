// A live camera through OpenCV's VideoCapture: a V4L2 device ("0" or
// "/dev/video0"), a GStreamer pipeline ending in appsink, a network stream
// (FFmpeg) or a video file (FFmpeg), each opened by the backend it names,
// with the exposure and gain set where the device has those controls (the
// paper adjusts shutter, gain and iris as the light changes).
//
// Each frame is stamped by the device where it can be (the capture's
// CAP_PROP_POS_MSEC: a V4L2 buffer's time, a file's presentation time),
// mapped onto the robot's time base by a DeviceClock, else by its arrival. A
// video file plays in real time, each frame handed over when its
// presentation time has come since the first, as a camera delivers them.
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "robot/input/device_clock.h"

namespace cv {
class VideoCapture;
}

namespace lineloc {

struct VideoCameraOptions {
  // A device index, a device path, a GStreamer pipeline, a URL or a file.
  std::string source;
  // CAP_PROP_EXPOSURE and CAP_PROP_GAIN in the device's own units (V4L2:
  // exposure in 100 us); negative: left as the device has them (automatic
  // where it is).
  double exposure = -1.0;
  double gain = -1.0;
};

struct CapturedFrame {
  cv::Mat image;
  // On the robot's time base: the exposure, and when the frame was taken
  // from the device.
  int64_t stamp_ns = 0;
  int64_t arrival_ns = 0;
};

class VideoCamera {
 public:
  // Throws std::runtime_error naming the source when it cannot be opened, or
  // a control that is asked for and that the device refuses.
  VideoCamera(const VideoCameraOptions& options, const RobotTimeBase& time_base);
  ~VideoCamera();
  VideoCamera(const VideoCamera&) = delete;
  VideoCamera& operator=(const VideoCamera&) = delete;

  // The next frame, waiting for it; nullopt at the end of a file or when the
  // device stops delivering.
  std::optional<CapturedFrame> read();

 private:
  std::string source_;
  const RobotTimeBase& time_base_;
  std::unique_ptr<cv::VideoCapture> capture_;
  bool file_ = false;
  DeviceClock clock_;
  std::optional<int64_t> first_device_ns_;
  int64_t first_arrival_ns_ = 0;
  int64_t last_device_ns_ = -1;
};

}  // namespace lineloc
