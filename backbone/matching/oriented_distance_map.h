// Oriented chamfer distance to the image segments a robot saw (Shotton, Blake
// & Cipolla, "Multiscale Categorical Object Recognition Using Contour
// Fragments", PAMI 30(7), 2008, §3.2): how far a pixel is from the nearest
// segment whose direction is close to a given one.
//
// Directions (mod pi) fall into kOrientationBins bins of width w = pi / bins.
// Every segment is drawn into the bin of its direction and the neighbouring
// bin nearer to it, so a query for direction theta (looked up in the bin whose
// centre is nearest) sees every segment within |phi - theta| <= w / 2 and none
// beyond 3 w / 2. Each bin's map is the Euclidean distance transform of its
// segments (cv::distanceTransform, Borgefors' 5x5 chamfer mask), truncated at
// truncation_px, kept at 1 / downsample of the image resolution.
#pragma once

#include <Eigen/Core>
#include <array>
#include <opencv2/core.hpp>
#include <vector>

#include "common/messages/messages.h"

namespace lineloc {

struct DistanceMapOptions {
  // Segments shorter than this (pixels) are left out.
  double min_segment_length_px = 15.0;
  // Distances beyond this are reported as this (pixels).
  double truncation_px = 12.0;
  // 1: full resolution; 2: half resolution (four times fewer pixels to fill).
  int downsample = 2;
};

class OrientedDistanceMap {
 public:
  static constexpr int kOrientationBins = 8;

  OrientedDistanceMap(const std::vector<ImageSegment>& segments, int width_px, int height_px,
                      const DistanceMapOptions& options);

  // Distance (pixels, <= truncation) from `pixel` to the nearest segment with
  // a direction near `direction_rad`; the truncation outside the image.
  float distance(const Eigen::Vector2d& pixel, double direction_rad) const;

  // Bin of a direction (radians, any value): round(theta / w) mod bins.
  static int binOf(double direction_rad);

  float truncationPx() const { return truncation_px_; }

 private:
  float truncation_px_;
  int downsample_;
  std::array<cv::Mat1f, kOrientationBins> maps_;
};

}  // namespace lineloc
