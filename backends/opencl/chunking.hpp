// The OpenCL backend's limits on a chunk of work (common/chunking.hpp cuts the work).
//
// OpenCL caps every buffer at CL_DEVICE_MAX_MEM_ALLOC_SIZE (a quarter of the memory is common; PoCL
// here: 2 GiB). Points, fields and particles are cut into chunks of whole rows, an RBF block into
// tiles of rows by columns. Kernels index with 32-bit ints, so a chunk also stays below
// kMaxChunkItems items.
#pragma once

#include "common/chunking.hpp"

#include <Eigen/Core>

#include <cstdint>

namespace posekit::opencl {

/// The smallest buffer limit a device may be given (OpenClDeviceOptions::max_buffer_bytes).
constexpr std::uint64_t kMinimumBufferBytes = 4096;

/// The largest number of items in one chunk: keeps every index a kernel computes in an int.
constexpr Eigen::Index kMaxChunkItems = Eigen::Index{1} << 28;

/// The limits of one chunk when no buffer may exceed `max_bytes`.
inline backends::ChunkLimits chunk_limits(std::uint64_t max_bytes) {
  return {max_bytes, kMaxChunkItems};
}

using backends::assembly_tiles;
using backends::items_per_chunk;
using backends::round_up;
using backends::TileShape;

}  // namespace posekit::opencl
