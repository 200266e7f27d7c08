#include "robot/input/video_camera.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <opencv2/videoio.hpp>
#include <optional>
#include <stdexcept>
#include <thread>

namespace lineloc {
namespace {

bool isDeviceIndex(const std::string& source) {
  return !source.empty() && source.size() <= 3 &&
         std::all_of(source.begin(), source.end(), [](unsigned char c) { return std::isdigit(c); });
}

// The backend a source names: a device index or /dev path V4L2, a pipeline
// (elements joined by '!') GStreamer, a file or URL FFmpeg. Nothing for a path
// that is none of these: no backend is asked to guess.
std::optional<int> backendOf(const std::string& source, bool file) {
  if (isDeviceIndex(source) || source.starts_with("/dev/")) {
    return cv::CAP_V4L2;
  }
  if (source.find('!') != std::string::npos) {
    return cv::CAP_GSTREAMER;
  }
  if (file || source.find("://") != std::string::npos) {
    return cv::CAP_FFMPEG;
  }
  return std::nullopt;
}

void setControl(cv::VideoCapture& capture, int property, double value, const char* name,
                const std::string& source) {
  if (value < 0.0) {
    return;
  }
  if (!capture.set(property, value)) {
    throw std::runtime_error(
        fmt::format("camera '{}' refuses {} {} (it has no such control, or not that value)", source,
                    name, value));
  }
}

}  // namespace

VideoCamera::VideoCamera(const VideoCameraOptions& options, const RobotTimeBase& time_base)
    : source_(options.source),
      time_base_(time_base),
      capture_(std::make_unique<cv::VideoCapture>()),
      file_(std::filesystem::is_regular_file(options.source)) {
  const std::optional<int> backend = backendOf(source_, file_);
  if (!backend) {
    throw std::runtime_error(fmt::format(
        "camera_source '{}': no such file, and not a device (an index, /dev/...), a GStreamer "
        "pipeline (elements joined by '!') or a URL",
        source_));
  }
  const bool opened = isDeviceIndex(source_) ? capture_->open(std::stoi(source_), *backend)
                                             : capture_->open(source_, *backend);
  if (!opened || !capture_->isOpened()) {
    throw std::runtime_error(fmt::format(
        "camera_source '{}': cannot be opened (not a camera device, a GStreamer pipeline, a "
        "stream or a video file OpenCV reads)",
        source_));
  }
  setControl(*capture_, cv::CAP_PROP_EXPOSURE, options.exposure, "camera_exposure", source_);
  setControl(*capture_, cv::CAP_PROP_GAIN, options.gain, "camera_gain", source_);
}

VideoCamera::~VideoCamera() = default;

std::optional<CapturedFrame> VideoCamera::read() {
  CapturedFrame frame;
  if (!capture_->read(frame.image) || frame.image.empty()) {
    return std::nullopt;
  }
  frame.arrival_ns = time_base_.now();
  // The device's stamp, when it gives one that moves on; else the arrival.
  const int64_t device_ns = std::llround(capture_->get(cv::CAP_PROP_POS_MSEC) * 1e6);
  if (device_ns <= last_device_ns_) {
    frame.stamp_ns = frame.arrival_ns;
    return frame;
  }
  last_device_ns_ = device_ns;
  if (file_) {
    // Hand the frame over once its presentation time has come.
    if (!first_device_ns_) {
      first_device_ns_ = device_ns;
      first_arrival_ns_ = frame.arrival_ns;
    }
    const int64_t due_ns = first_arrival_ns_ + (device_ns - *first_device_ns_);
    if (due_ns > frame.arrival_ns) {
      std::this_thread::sleep_for(std::chrono::nanoseconds(due_ns - frame.arrival_ns));
      frame.arrival_ns = time_base_.now();
    }
  }
  frame.stamp_ns = clock_.map(device_ns, frame.arrival_ns);
  return frame;
}

}  // namespace lineloc
