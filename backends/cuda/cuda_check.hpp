// Failed CUDA runtime calls turned into DeviceError messages that name the call, the error, the
// file and the line.
#pragma once

#include <cuda_runtime_api.h>

#include <string>

namespace posekit::cuda {

/// "cudaErrorMemoryAllocation: out of memory" for an error code.
std::string describe(cudaError_t error);

/// Throws DeviceError("CALL failed with NAME: TEXT at FILE:LINE") unless error is cudaSuccess.
void check(cudaError_t error, const char* call, const char* file, int line);

}  // namespace posekit::cuda

/// Checks the cudaError_t a CUDA call (or a kernel launcher of cuda_kernels.hpp) returns; the
/// message quotes the call.
#define POSEKIT_CUDA_CHECK(call) ::posekit::cuda::check((call), #call, __FILE__, __LINE__)
