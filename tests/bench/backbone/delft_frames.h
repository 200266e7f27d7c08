// The frames of a simulated drive through the bundled Delft model with the
// robot's front end run on each (lines and corners, as a robot sends them),
// for the backbone's benchmarks, and predictions drawn around their truth.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "common/camera/camera_calibration.h"
#include "common/geometry/pose.h"
#include "common/geometry/sunlight.h"
#include "common/messages/messages.h"

namespace lineloc::test {

struct DelftFrame {
  cv::Mat image;
  Eigen::Isometry3d truth;
  std::vector<ImageSegment> segments;
  std::vector<ImageCorner> corners;
  // The front end's time on this frame, one thread.
  int64_t front_end_ns = 0;
};

struct DelftFrames {
  CameraCalibration calibration;
  std::vector<DelftFrame> frames;
  // The sun the drive is rendered under, which the backbone is told.
  Sunlight sunlight;
};

// A `duration_s` drive (half a second standing first) at `camera_rate_hz`.
DelftFrames simulateDelftFrames(double duration_s, double camera_rate_hz);

// `truth` moved by one draw of the given uncertainty, with that covariance.
PoseWithCovariance predictedAround(const Eigen::Isometry3d& truth, double position_sigma_m,
                                   double rotation_sigma_rad, std::mt19937& random);

}  // namespace lineloc::test
