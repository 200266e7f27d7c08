// lineloc-flow: optical flow of two frames, or the disparity of a rectified
// stereo pair, with the SAD kernels of robot/vision/block_matching.
//
//   lineloc-flow A B --out flow.png [--flo flow.flo]
//   lineloc-flow --stereo L R --out disp.png [--pfm disp.pfm]
#include <fmt/format.h>

#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/config/program_options.h"
#include "robot/vision/block_matching/kernel_timing.h"
#include "robot/vision/flow/correlation_flow.h"
#include "robot/vision/flow/flo_io.h"
#include "robot/vision/flow/flow_render.h"
#include "robot/vision/stereo/disparity_render.h"
#include "robot/vision/stereo/pfm_io.h"

namespace {

struct Config {
  std::vector<std::string> images;
  bool stereo = false;
  std::string out = "flow.png";
  std::string flo;
  std::string pfm;
  std::string simd_path = "best";
  int block_size_px = 16;
  int search_radius_px = 16;
  std::vector<float> direction;
  double threshold_sigmas = 3.0;
  int stereo_block_size_px = 15;
  int min_disparity_px = 0;
  int num_disparities = 64;
  int uniqueness_percent = 10;
};

lineloc::SimdPath parsePath(const std::string& name) {
  for (lineloc::SimdPath path : lineloc::supportedSimdPaths()) {
    if (lineloc::simdPathName(path) == name) {
      return path;
    }
  }
  if (name == "best") {
    return lineloc::bestSimdPath();
  }
  throw std::invalid_argument(fmt::format("simd_path '{}' is not supported here", name));
}

cv::Mat readImage(const std::string& path, int mode) {
  cv::Mat image = cv::imread(path, mode);
  if (image.empty()) {
    throw std::runtime_error(fmt::format("cannot read image '{}'", path));
  }
  return image;
}

void printTiming(const char* what, const lineloc::RunSample& sample, lineloc::SimdPath path) {
  std::cout << fmt::format("lineloc-flow: {} in {:.2f} ms ({:.1f} M TSC cycles), {} path\n", what,
                           sample.duration_ns * 1e-6, sample.duration_cycles * 1e-6,
                           lineloc::simdPathName(path));
}

void runStereo(const Config& config, lineloc::SimdPath path) {
  const lineloc::StereoOptions options{config.stereo_block_size_px, config.min_disparity_px,
                                       config.num_disparities, config.uniqueness_percent};
  const cv::Mat left = readImage(config.images[0], cv::IMREAD_GRAYSCALE);
  const cv::Mat right = readImage(config.images[1], cv::IMREAD_GRAYSCALE);
  const lineloc::RunTimer timer;
  const lineloc::DisparityMap map = lineloc::SadStereoMatcher(options, path).compute(left, right);
  printTiming("disparity", timer.elapsed(), path);
  cv::imwrite(config.out,
              lineloc::renderDisparity(map, config.min_disparity_px + config.num_disparities));
  if (!config.pfm.empty()) {
    lineloc::writePfm(config.pfm, lineloc::disparityForPfm(map.disparity_px, map.valid));
  }
}

void runFlow(const Config& config, lineloc::SimdPath path) {
  lineloc::FlowOptions options;
  options.block_size_px = config.block_size_px;
  options.search_radius_px = config.search_radius_px;
  options.motion.threshold_sigmas = config.threshold_sigmas;
  if (config.direction.size() == 2) {
    options.expected_direction = cv::Point2f(config.direction[0], config.direction[1]);
  } else if (!config.direction.empty()) {
    throw std::invalid_argument("direction needs two numbers: dx dy");
  }
  const cv::Mat first = readImage(config.images[0], cv::IMREAD_COLOR);
  const cv::Mat second = readImage(config.images[1], cv::IMREAD_COLOR);
  const lineloc::RunTimer timer;
  const lineloc::FlowField field = lineloc::computeCorrelationFlow(first, second, options, path);
  printTiming("flow", timer.elapsed(), path);
  int moving = 0;
  for (const lineloc::FlowBlock& block : field.blocks) {
    moving += block.moving;
  }
  std::cout << fmt::format(
      "lineloc-flow: noise sigma {:.2f}, threshold {:.1f}, {} of {} blocks moving\n",
      field.motion.noise_sigma, field.motion.threshold, moving, field.blocks.size());
  cv::imwrite(config.out, lineloc::renderFlow(field, first));
  if (!config.flo.empty()) {
    lineloc::writeFlo(config.flo, field.flow_px, field.known);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Config config;
  lineloc::ProgramOptions options("lineloc-flow",
                                  "SAD optical flow of two frames, or disparity of a stereo pair");
  options.app()
      .add_option("images", config.images, "two frames (A B), or left and right with --stereo")
      ->expected(2)
      ->required();
  options.app().add_flag("--stereo", config.stereo, "the images are a rectified stereo pair");
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
    const lineloc::SimdPath path = parsePath(config.simd_path);
    if (config.stereo) {
      runStereo(config, path);
    } else {
      runFlow(config, path);
    }
    std::cout << "lineloc-flow: wrote " << config.out << '\n';
    return 0;
  } catch (const std::exception& error) {
    std::cerr << "lineloc-flow: " << error.what() << '\n';
    return 1;
  }
}
