#include "robot/vision/flow/flow_render.h"

#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace lineloc {
namespace {

// Middlebury's wheel: red-yellow 15, yellow-green 6, green-cyan 4, cyan-blue
// 11, blue-magenta 13, magenta-red 6 steps (RGB).
std::vector<cv::Vec3f> colourWheel() {
  constexpr std::array<int, 6> kSteps = {15, 6, 4, 11, 13, 6};
  std::vector<cv::Vec3f> wheel;
  for (int segment = 0; segment < 6; ++segment) {
    for (int i = 0; i < kSteps[segment]; ++i) {
      const float up = 255.0f * i / kSteps[segment];
      const float down = 255.0f - up;
      const std::array<cv::Vec3f, 6> colours = {cv::Vec3f(255, up, 0), cv::Vec3f(down, 255, 0),
                                                cv::Vec3f(0, 255, up), cv::Vec3f(0, down, 255),
                                                cv::Vec3f(up, 0, 255), cv::Vec3f(255, 0, down)};
      wheel.push_back(colours[segment]);
    }
  }
  return wheel;
}

cv::Vec3b colourOf(float u, float v, const std::vector<cv::Vec3f>& wheel) {
  const float radius = std::hypot(u, v);
  const float angle = std::atan2(-v, -u) / static_cast<float>(CV_PI);
  const float position = (angle + 1.0f) / 2.0f * static_cast<float>(wheel.size() - 1);
  const int k0 = static_cast<int>(position);
  const int k1 = (k0 + 1) % static_cast<int>(wheel.size());
  const float f = position - static_cast<float>(k0);
  cv::Vec3b bgr;
  for (int c = 0; c < 3; ++c) {
    float value = ((1.0f - f) * wheel[k0][c] + f * wheel[k1][c]) / 255.0f;
    value = radius <= 1.0f ? 1.0f - radius * (1.0f - value) : 0.75f * value;
    bgr[2 - c] = cv::saturate_cast<uint8_t>(255.0f * value);
  }
  return bgr;
}

}  // namespace

cv::Mat flowColourCode(const cv::Mat& flow_px, const cv::Mat& known, double max_magnitude_px) {
  static const std::vector<cv::Vec3f> wheel = colourWheel();
  cv::Mat picture(flow_px.size(), CV_8UC3, cv::Scalar(0, 0, 0));
  const float scale = static_cast<float>(1.0 / max_magnitude_px);
  for (int y = 0; y < flow_px.rows; ++y) {
    for (int x = 0; x < flow_px.cols; ++x) {
      if (known.at<uint8_t>(y, x)) {
        const cv::Vec2f flow = flow_px.at<cv::Vec2f>(y, x);
        picture.at<cv::Vec3b>(y, x) = colourOf(flow[0] * scale, flow[1] * scale, wheel);
      }
    }
  }
  return picture;
}

cv::Mat renderFlow(const FlowField& field, const cv::Mat& first_frame) {
  double max_magnitude_px = 1.0;
  for (const FlowBlock& block : field.blocks) {
    if (block.known) {
      max_magnitude_px =
          std::max<double>(max_magnitude_px, std::hypot(block.flow_px.x, block.flow_px.y));
    }
  }
  cv::Mat arrows;
  if (first_frame.channels() == 1) {
    cv::cvtColor(first_frame, arrows, cv::COLOR_GRAY2BGR);
  } else {
    arrows = first_frame.clone();
  }
  for (const FlowBlock& block : field.blocks) {
    if (block.moving && block.known) {
      const cv::Point2f centre(block.block.x + block.block.width * 0.5f,
                               block.block.y + block.block.height * 0.5f);
      const float scale = static_cast<float>(block.block.width / max_magnitude_px);
      cv::arrowedLine(arrows, centre, centre + scale * block.flow_px, cv::Scalar(0, 255, 0), 1,
                      cv::LINE_AA, 0, 0.3);
    }
  }
  cv::Mat picture;
  cv::hconcat(flowColourCode(field.flow_px, field.known, max_magnitude_px), arrows, picture);
  return picture;
}

}  // namespace lineloc
