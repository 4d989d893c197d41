// The OpenCL program text, embedded at build time (embed_kernel_sources.cmake writes the
// definition from kernel_math.h and kernels/opencl/*.cl); no file is read at run time.
#pragma once

namespace posekit::opencl {

/// The whole program: kernel_math.h, then kernels/opencl's files in the order of CMakeLists.txt.
const char* program_source();

}  // namespace posekit::opencl
