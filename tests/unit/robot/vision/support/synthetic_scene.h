// Synthetic camera images with known straight edges and corners, for the
// vision front end's accuracy tests and benchmarks.
//
// Polygons are filled at `supersampling` times the resolution (OpenCV
// fillPoly with sub-pixel vertices) and area-averaged down, so each pixel
// holds its coverage to within 1/(2 supersampling) px of edge position; then
// Gaussian blur (the lens) and Gaussian noise (the sensor) are added.
// Pixel centres are at integer coordinates.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace lineloc::testing {

struct SceneSegment {
  Eigen::Vector2d start;
  Eigen::Vector2d end;
};

struct SyntheticScene {
  cv::Mat image;  // CV_8UC1
  std::vector<SceneSegment> segments;
  std::vector<Eigen::Vector2d> corners;
};

struct SceneOptions {
  cv::Size size{320, 240};
  double blur_sigma_px = 1.0;
  double noise_sigma = 2.0;  // grey levels
  int supersampling = 16;
};

// A polygon drawn with one grey level; its edges and vertices are the truth.
struct ScenePolygon {
  std::vector<Eigen::Vector2d> vertices;
  double grey;
};

// Renders polygons over a uniform background, in order (later ones on top).
SyntheticScene renderPolygons(const SceneOptions& options, double background_grey,
                              const std::vector<ScenePolygon>& polygons, uint32_t seed);

// The range of a rectangle's side lengths (px).
struct SideRange {
  double min_px = 40.0;
  double max_px = 110.0;
};

// `count` non-overlapping rotated rectangles of random size (sides in
// `sides`), angle and polarity (dark 30..80 or bright 180..230 on a 128
// background).
SyntheticScene renderRectangles(const SceneOptions& options, int count, uint32_t seed,
                                const SideRange& sides = {});

}  // namespace lineloc::testing
