// lineloc-flow: optical flow of two frames, or the disparity of a rectified
// stereo pair, with the SAD kernels of robot/vision/block_matching.
//
//   lineloc-flow A B --out flow.png [--flo flow.flo]
//   lineloc-flow --stereo L R --out disp.png [--pfm disp.pfm]
#include <iostream>

#include "common/config/program_options.h"
#include "robot/vision/flow/flow_tool.h"

int main(int argc, char** argv) {
  lineloc::FlowToolConfig config;
  lineloc::ProgramOptions options("lineloc-flow",
                                  "SAD optical flow of two frames, or disparity of a stereo pair");
  options.addPositional("images", config.images,
                        "two frames (A B), or left and right with --stereo", 2, true);
  options.addFlag("stereo", config.stereo, "the images are a rectified stereo pair");
  options.add("out", config.out, "PNG picture of the flow (colour code | arrows) or disparity");
  options.add("flo", config.flo, "also write the flow here, Middlebury .flo (empty: no)");
  options.add("pfm", config.pfm, "also write the disparity here, PFM (empty: no)");
  options.add("simd_path", config.simd_path, "SAD kernels: best, scalar, sse2, avx2, avx512bw");
  options.add("block_size_px", config.block_size_px, "flow block side (pixels)");
  options.add("search_radius_px", config.search_radius_px, "flow search window +-R (pixels)");
  options.add("direction", config.direction,
              "expected motion direction dx dy: 1-D search along it (empty: full 2-D search)");
  options.add("threshold_sigmas", config.threshold_sigmas,
              "motion threshold in noise standard deviations of the frame difference");
  options.add("stereo_block_size_px", config.stereo_block_size_px, "stereo block side, odd");
  options.add("min_disparity_px", config.min_disparity_px, "smallest disparity searched");
  options.add("num_disparities", config.num_disparities, "number of disparities searched");
  options.add("uniqueness_percent", config.uniqueness_percent,
              "stereo: reject a minimum another disparity comes within this percent of");
  if (const auto exit_code = options.parse(argc, argv)) {
    return *exit_code;
  }
  try {
    lineloc::runFlowTool(config, std::cout);
    return 0;
  } catch (const std::exception& error) {
    std::cerr << "lineloc-flow: " << error.what() << '\n';
    return 1;
  }
}
