// The OpenCV sample images (Debian package opencv-doc) that tests and
// benchmarks of robot/vision read; the folder is compiled in as
// LINELOC_OPENCV_SAMPLE_DATA_DIR by lineloc_use_opencv_sample_data().
#pragma once

#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>

namespace lineloc {

// Throws std::runtime_error naming the file when it cannot be read.
inline cv::Mat readSampleImage(const std::string& name, int mode) {
  const std::string path = std::string(LINELOC_OPENCV_SAMPLE_DATA_DIR) + "/" + name;
  cv::Mat image = cv::imread(path, mode);
  if (image.empty()) {
    throw std::runtime_error("cannot read " + path + " (Debian package opencv-doc)");
  }
  return image;
}

}  // namespace lineloc
