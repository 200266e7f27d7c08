// Internal: the kernel table of each path, one translation unit per
// instruction set so that each is compiled with exactly its target flags.
#pragma once

#include "robot/vision/block_matching/sad_kernels.h"

namespace lineloc::sad_paths {

const SadKernels& scalarKernels();
#if defined(LINELOC_SAD_X86)
const SadKernels& sse2Kernels();
const SadKernels& avx2Kernels();
const SadKernels& avx512BwKernels();
#endif

}  // namespace lineloc::sad_paths
