// The camera frames the robot reads: a folder of images, or an EuRoC/ASL camera
// folder (cam0/ with data.csv "#timestamp [ns],filename" and data/).
#pragma once

#include <cstdint>
#include <istream>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace lineloc {

struct FrameRef {
  std::string path;
  // Exposure time from the dataset; nullopt for a plain folder of images.
  std::optional<int64_t> stamp_ns;
};

// Lists the frames in order. `path` is an EuRoC dataset root (with cam0/), a
// camera folder (with data.csv), or a folder of .png/.jpg/.jpeg/.pgm/.bmp files
// taken in name order (a numeric name is read as a nanosecond stamp, as EuRoC
// names its files). Throws std::runtime_error naming the file and line of any
// problem: missing folder, no images, malformed or non-increasing data.csv rows.
std::vector<FrameRef> listImageSequence(const std::string& path);

// Parses an EuRoC camera data.csv ("#timestamp [ns],filename" rows, stamps
// strictly increasing); `source` names it in errors, files are under `data_dir`.
std::vector<FrameRef> parseEurocCameraCsv(std::istream& stream, const std::string& source,
                                          const std::string& data_dir);

// Reads an image as 8-bit grey (colour converted) through readImageFile.
// Throws std::runtime_error naming the file when it cannot be read or decoded,
// or its header claims more than kDefaultMaxImagePixels.
cv::Mat readGreyImage(const std::string& path);

}  // namespace lineloc
