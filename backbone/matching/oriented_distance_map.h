// Oriented chamfer distance to the image segments a robot saw (Shotton, Blake
// & Cipolla, "Multiscale Categorical Object Recognition Using Contour
// Fragments", PAMI 30(7), 2008, §3.2): how far a pixel is from the nearest
// segment whose direction is close to a given one.
//
// Directions (mod pi) fall into kOrientationBins bins of width w = pi / bins.
// Every segment is drawn into the bin of its direction and the neighbouring
// bin nearer to it, so a query for direction theta (looked up in the bin whose
// centre is nearest) sees every segment within |phi - theta| <= w / 2 and none
// beyond 3 w / 2. Each bin's map holds, at every cell, the exact Euclidean
// distance min(truncation_px, min_s |q - s|) from the cell's point q to the
// bin's segments s. Only cells within the truncation of a segment can differ
// from it, so each segment fills its own band of half-width truncation_px,
// row by row — far less work than a distance transform of the whole image
// when the truncation is a few pixels. The maps are kept at 1 / downsample of
// the image resolution: cell (i, j) holds the point (i, j) * downsample; and
// in bytes, the distance d as round(255 d / truncation_px), which quantises it
// to truncation / 510 either way (0.006 px for the sharpest map, 3 px; d is
// computed in single precision, to 1e-4 px): eight
// float maps of a 640 x 480 image are 9.8 MB to fill for every frame, eight
// byte maps 2.5 MB.
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

  // Distance (pixels, <= truncation, quantised as above) from `pixel` to the nearest segment with
  // a direction near `direction_rad`; the truncation outside the image.
  float distance(const Eigen::Vector2d& pixel, double direction_rad) const;

  // Covered length of the segment a-b (pixels): its length L times the mean of
  // 1 - d_theta(q) / truncation over n = floor(L / spacing_px) samples q at
  // the centres of n equal pieces, theta its direction; 0 when n = 0.
  double coveredLength(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double spacing_px) const;

  // Bin of a direction (radians, any value): round(theta / w) mod bins.
  static int binOf(double direction_rad);

 private:
  static constexpr int kTruncationLevel = 255;

  // Level of the cell nearest to `scaled_pixel` (image pixel / downsample);
  // the truncation's outside the map.
  int lookup(const cv::Mat1b& map, const Eigen::Vector2d& scaled_pixel) const;
  // map = min(map, level of the distance to the segment a-b) over the segment's band.
  void drawDistanceBand(cv::Mat1b& map, const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;

  float truncation_px_;
  // Pixels per level: truncation_px / 255.
  float level_px_;
  int downsample_;
  std::array<cv::Mat1b, kOrientationBins> maps_;
};

}  // namespace lineloc
