// Middlebury optical-flow files (.flo, Baker et al., "A Database and
// Evaluation Methodology for Optical Flow", IJCV 2011): the bytes "PIEH"
// (the float 202021.25), int32 width, int32 height, then width * height
// pairs of float32 (u, v), row by row from the top, all little endian.
// Components above 1e9 mark unknown flow.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <span>
#include <string>
#include <vector>

namespace lineloc {

inline constexpr float kUnknownFlow = 1e10f;

// `flow_px`: CV_32FC2; where `known` (CV_8U, optional) is zero the flow is
// written as unknown. Throws std::runtime_error when the file cannot be
// written.
std::vector<uint8_t> encodeFlo(const cv::Mat& flow_px, const cv::Mat& known = {});
void writeFlo(const std::string& path, const cv::Mat& flow_px, const cv::Mat& known = {});

// CV_32FC2 (unknown flow kept as stored). Throws std::runtime_error naming
// what is wrong (and the file) for anything but a well-formed .flo.
cv::Mat decodeFlo(std::span<const uint8_t> bytes);
cv::Mat readFlo(const std::string& path);

}  // namespace lineloc
