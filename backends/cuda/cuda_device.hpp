// The CUDA backend as the registry and the tests see it.
#pragma once

#include "device/backend_factory.hpp"

#include <posekit/device.hpp>

#include <cstdint>
#include <memory>

namespace posekit::cuda {

/// The registry entry "cuda": available when discovery (cuda_discovery.hpp) finds a GPU this
/// build has kernels for.
detail::BackendFactory backend_factory();

/// Choices that the registry leaves at their defaults and tests change.
struct CudaDeviceOptions {
  /// Largest scratch buffer an operation allocates, in bytes: 0 for kDefaultChunkBytes
  /// (chunking.hpp, capped at an eighth of the GPU's memory), else at least kMinimumChunkBytes.
  /// A small value makes every operation cut its work into many chunks.
  std::uint64_t max_chunk_bytes = 0;
  /// Blocks of the RK45 kernel: 0 for as many as the GPU holds at once, else at least 1. With
  /// few blocks, threads integrate many particles each, one after the other.
  int rk45_blocks = 0;
};

/// A device on the GPU that discovery chooses, its kernels checked for this GPU now. Throws
/// DeviceError when there is none or the runtime refuses it, ArgumentError for options out of
/// range.
std::unique_ptr<Device> make_cuda_device(const CudaDeviceOptions& options = {});

}  // namespace posekit::cuda
