#include "robot/vision/block_matching/sad_kernels.h"

#include <fmt/format.h>

#include <stdexcept>

#include "robot/vision/block_matching/sad_paths.h"

namespace lineloc {
namespace {

bool processorRuns(SimdPath path) {
#if defined(LINELOC_SAD_X86)
  switch (path) {
    case SimdPath::kScalar:
      return true;
    case SimdPath::kSse2:
      return __builtin_cpu_supports("sse2");
    case SimdPath::kAvx2:
      return __builtin_cpu_supports("avx2");
    case SimdPath::kAvx512Bw:
      return __builtin_cpu_supports("avx512bw");
  }
  return false;
#else
  return path == SimdPath::kScalar;
#endif
}

const SadKernels& kernelsOf(SimdPath path) {
#if defined(LINELOC_SAD_X86)
  switch (path) {
    case SimdPath::kSse2:
      return sad_paths::sse2Kernels();
    case SimdPath::kAvx2:
      return sad_paths::avx2Kernels();
    case SimdPath::kAvx512Bw:
      return sad_paths::avx512BwKernels();
    case SimdPath::kScalar:
      break;
  }
#endif
  (void)path;
  return sad_paths::scalarKernels();
}

}  // namespace

std::string_view simdPathName(SimdPath path) {
  switch (path) {
    case SimdPath::kScalar:
      return "scalar";
    case SimdPath::kSse2:
      return "sse2";
    case SimdPath::kAvx2:
      return "avx2";
    case SimdPath::kAvx512Bw:
      return "avx512bw";
  }
  return "unknown";
}

bool gridSearchSupports(int block_width_px, int block_height_px) {
  const auto supported = [](int size) { return size == 8 || size == 16; };
  return supported(block_width_px) && supported(block_height_px);
}

int simdPathWidthBytes(SimdPath path) {
  switch (path) {
    case SimdPath::kSse2:
      return 16;
    case SimdPath::kAvx2:
      return 32;
    case SimdPath::kAvx512Bw:
      return 64;
    case SimdPath::kScalar:
      break;
  }
  return 1;
}

std::vector<SimdPath> supportedSimdPaths() {
  std::vector<SimdPath> paths;
  for (SimdPath path : {SimdPath::kScalar, SimdPath::kSse2, SimdPath::kAvx2, SimdPath::kAvx512Bw}) {
    if (processorRuns(path)) {
      paths.push_back(path);
    }
  }
  return paths;
}

SimdPath bestSimdPath() {
  static const SimdPath best = supportedSimdPaths().back();
  return best;
}

const SadKernels& sadKernels(SimdPath path) {
  if (!processorRuns(path)) {
    throw std::invalid_argument(fmt::format(
        "SAD path '{}' is not supported by this build or processor", simdPathName(path)));
  }
  return kernelsOf(path);
}

const SadKernels& sadKernels() {
  return kernelsOf(bestSimdPath());
}

}  // namespace lineloc
