// Fuzz target: arbitrary images (size, type, distortion, pixels all from the
// input bytes) through the vision front end. Only std::invalid_argument for a
// refused image or calibration is expected; any other exception, crash or
// non-finite output is a bug.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <opencv2/core.hpp>
#include <stdexcept>

#include "robot/vision/features/feature_extractor.h"

namespace {

constexpr int kMaxSidePx = 72;
constexpr size_t kHeaderBytes = 4 + 4 * sizeof(int8_t);

struct Reader {
  const uint8_t* data;
  size_t size;
  size_t at = 0;
  uint8_t next() { return at < size ? data[at++] : 0; }
};

void checkFinite(const lineloc::FrameFeatures& features) {
  for (const lineloc::ImageSegment& s : features.segments) {
    if (!s.start.allFinite() || !s.end.allFinite() || !s.start_covariance.allFinite() ||
        !s.end_covariance.allFinite() || !std::isfinite(s.contrast)) {
      std::abort();
    }
  }
  for (const lineloc::ImageCorner& c : features.corners) {
    if (!c.position.allFinite() || !c.covariance.allFinite() || !std::isfinite(c.strength)) {
      std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Reader reader{data, size};
  const int width = reader.next() % kMaxSidePx + 1;
  const int height = reader.next() % kMaxSidePx + 1;
  const int type_choice = reader.next() % 6;
  const bool mismatched_size = reader.next() % 8 == 0;
  lineloc::CameraCalibration calibration;
  calibration.camera = {
      0.8 * width + 1.0, 0.8 * width + 1.0, 0.5 * width, 0.5 * height, 0.0, width, height};
  for (int k = 0; k < 4; ++k) {
    calibration.distortion.push_back(static_cast<int8_t>(reader.next()) / 400.0);
  }
  static constexpr int kTypes[] = {CV_8UC1, CV_8UC1, CV_8UC3, CV_8UC4, CV_16UC1, CV_8UC2};
  cv::Mat image(mismatched_size ? height + 1 : height, width, kTypes[type_choice]);
  const size_t bytes = image.total() * image.elemSize();
  for (size_t i = 0; i < bytes; ++i) {
    image.data[i] = size > kHeaderBytes ? data[kHeaderBytes + i % (size - kHeaderBytes)] : 0;
  }
  try {
    lineloc::FeatureExtractor extractor(calibration);
    checkFinite(extractor.extract(image));
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
