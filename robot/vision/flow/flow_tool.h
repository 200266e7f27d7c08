// What lineloc-flow does: the optical flow of two frames
// (correlation_flow.h) or the disparity of a rectified stereo pair
// (robot/vision/stereo/sad_stereo.h) with the SAD kernels of
// robot/vision/block_matching, timed, drawn to a picture and, when asked,
// written as Middlebury .flo or PFM.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace lineloc {

struct FlowToolConfig {
  // Two frames (A B), or the left and right images of a rectified pair.
  std::vector<std::string> images;
  bool stereo = false;
  std::string out = "flow.png";
  std::string flo;
  std::string pfm;
  // SAD kernels: best, scalar, sse2, avx2 or avx512bw.
  std::string simd_path = "best";
  int block_size_px = 16;
  int search_radius_px = 16;
  // Expected motion dx dy: a 1-D search along it; empty: a full 2-D search.
  std::vector<float> direction;
  double threshold_sigmas = 3.0;
  int stereo_block_size_px = 15;
  int min_disparity_px = 0;
  int num_disparities = 64;
  int uniqueness_percent = 10;
};

// Writes the timing and, for flow, the noise and moving blocks to `out`, and
// the picture and files. Throws std::invalid_argument naming an option out of
// its range, std::runtime_error naming a file that cannot be read.
void runFlowTool(const FlowToolConfig& config, std::ostream& out);

}  // namespace lineloc
