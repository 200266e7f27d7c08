// Correlation optical flow, Persa & Jonker §4: the flow of each block of the
// previous frame is the displacement of least SAD (eq. 7) summed over the
// colour channels, searched only in blocks where motion was detected
// (motion_detector.h), either over the full +-R window (block_matcher.h) or,
// when the expected direction u of the motion is known (the robot's own
// motion, or last frame's flow), along the line t u, t in [-R, R], with the
// displacement (round(t u_x), round(t u_y)). Sub-pixel: a parabola per axis
// through the SADs at -1, 0, +1 pixel around the best displacement (on the
// line's rounded pixels the SAD is not smooth in t). A 1-D minimum that is not
// a minimum across the line (the motion is off the expected direction) gives
// unknown flow.
//
// Blocks without detected motion get flow 0. A block whose minimum is on the
// window's edge or flat (textureless) gets no flow: unknown.
#pragma once

#include <opencv2/core.hpp>
#include <optional>

#include "robot/vision/block_matching/sad_kernels.h"
#include "robot/vision/flow/motion_detector.h"

namespace lineloc {

struct FlowOptions {
  int block_size_px = 16;
  int search_radius_px = 16;
  // A block is searched when at least this fraction of its pixels moves.
  double min_moving_fraction = 0.05;
  // Set: 1-D search along this direction (need not be unit length).
  std::optional<cv::Point2f> expected_direction;
  MotionOptions motion;
};

struct FlowBlock {
  cv::Rect block;
  cv::Point2f flow_px;  // (0, 0) for static blocks
  bool moving = false;  // motion detected, block searched
  bool known = false;   // flow_px is an estimate
};

struct FlowField {
  std::vector<FlowBlock> blocks;
  cv::Mat flow_px;  // CV_32FC2, each block's flow over its pixels
  cv::Mat known;    // CV_8U, 255 where flow_px is an estimate
  MotionMask motion;
};

// Frames: same size, CV_8UC3 (or CV_8UC1), at least one block; throws
// std::invalid_argument naming the problem otherwise.
FlowField computeCorrelationFlow(const cv::Mat& previous, const cv::Mat& current,
                                 const FlowOptions& options, SimdPath path = bestSimdPath());

}  // namespace lineloc
