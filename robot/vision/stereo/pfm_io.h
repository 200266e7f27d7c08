// Portable float map (PFM) files, the format of the Middlebury stereo
// benchmark's disparities: a text header "Pf" (one channel) or "PF" (three),
// then "<width> <height>", then a scale whose sign gives the byte order
// (negative: little endian), each followed by one whitespace character, then
// 32-bit floats, rows from the bottom of the image to the top. Middlebury
// marks pixels without a disparity as +infinity.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <span>
#include <string>
#include <vector>

namespace lineloc {

// `image`: CV_32FC1 or CV_32FC3; written little endian. Throws
// std::runtime_error when the file cannot be written.
void writePfm(const std::string& path, const cv::Mat& image);
std::vector<uint8_t> encodePfm(const cv::Mat& image);

// CV_32FC1 or CV_32FC3, top row first. Throws std::runtime_error naming what
// is wrong (and the file) for anything but a well-formed PFM.
cv::Mat readPfm(const std::string& path);
cv::Mat decodePfm(std::span<const uint8_t> bytes);

// The disparity map as Middlebury PFM: `valid` (CV_8U) zero -> +infinity.
cv::Mat disparityForPfm(const cv::Mat& disparity_px, const cv::Mat& valid);

}  // namespace lineloc
