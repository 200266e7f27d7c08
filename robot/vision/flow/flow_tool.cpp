#include "robot/vision/flow/flow_tool.h"

#include <fmt/format.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <ostream>

#include "common/image/image_file.h"
#include "robot/vision/block_matching/kernel_timing.h"
#include "robot/vision/flow/correlation_flow.h"
#include "robot/vision/flow/flo_io.h"
#include "robot/vision/flow/flow_render.h"
#include "robot/vision/stereo/disparity_render.h"
#include "robot/vision/stereo/pfm_io.h"

namespace lineloc {
namespace {

SimdPath parsePath(const std::string& name) {
  for (SimdPath path : supportedSimdPaths()) {
    if (simdPathName(path) == name) {
      return path;
    }
  }
  if (name == "best") {
    return bestSimdPath();
  }
  throw std::invalid_argument(fmt::format("simd_path '{}' is not supported here", name));
}

void printTiming(const char* what, const RunSample& sample, SimdPath path, std::ostream& out) {
  out << fmt::format("lineloc-flow: {} in {:.2f} ms ({:.1f} M TSC cycles), {} path\n", what,
                     sample.duration_ns * 1e-6, sample.duration_cycles * 1e-6, simdPathName(path));
}

void runStereo(const FlowToolConfig& config, SimdPath path, std::ostream& out) {
  const StereoOptions options{config.stereo_block_size_px, config.min_disparity_px,
                              config.num_disparities, config.uniqueness_percent};
  const cv::Mat left = readImageFile(config.images[0], cv::IMREAD_GRAYSCALE);
  const cv::Mat right = readImageFile(config.images[1], cv::IMREAD_GRAYSCALE);
  const RunTimer timer;
  const DisparityMap map = SadStereoMatcher(options, path).compute(left, right);
  printTiming("disparity", timer.elapsed(), path, out);
  cv::imwrite(config.out, renderDisparity(map, config.min_disparity_px + config.num_disparities));
  if (!config.pfm.empty()) {
    writePfm(config.pfm, disparityForPfm(map.disparity_px, map.valid));
  }
}

void runFlow(const FlowToolConfig& config, SimdPath path, std::ostream& out) {
  FlowOptions options;
  options.block_size_px = config.block_size_px;
  options.search_radius_px = config.search_radius_px;
  options.motion.threshold_sigmas = config.threshold_sigmas;
  if (config.direction.size() == 2) {
    options.expected_direction = cv::Point2f(config.direction[0], config.direction[1]);
  } else if (!config.direction.empty()) {
    throw std::invalid_argument("direction needs two numbers: dx dy");
  }
  const cv::Mat first = readImageFile(config.images[0], cv::IMREAD_COLOR);
  const cv::Mat second = readImageFile(config.images[1], cv::IMREAD_COLOR);
  const RunTimer timer;
  const FlowField field = computeCorrelationFlow(first, second, options, path);
  printTiming("flow", timer.elapsed(), path, out);
  int moving = 0;
  for (const FlowBlock& block : field.blocks) {
    moving += block.moving;
  }
  out << fmt::format("lineloc-flow: noise sigma {:.2f}, threshold {:.1f}, {} of {} blocks moving\n",
                     field.motion.noise_sigma, field.motion.threshold, moving, field.blocks.size());
  cv::imwrite(config.out, renderFlow(field, first));
  if (!config.flo.empty()) {
    writeFlo(config.flo, field.flow_px, field.known);
  }
}

}  // namespace

void runFlowTool(const FlowToolConfig& config, std::ostream& out) {
  if (config.images.size() != 2) {
    throw std::invalid_argument("images: two are needed");
  }
  const SimdPath path = parsePath(config.simd_path);
  if (config.stereo) {
    runStereo(config, path, out);
  } else {
    runFlow(config, path, out);
  }
  out << "lineloc-flow: wrote " << config.out << '\n';
}

}  // namespace lineloc
