// The CUDA backend's limits on a chunk of work (common/chunking.hpp cuts the work). Kernels index within a chunk with 32-bit ints and the grid's y extent is limited to
// 65,535 blocks, so a chunk holds at most kMaxChunkItems items and a tile at most kMaxTileColumns
// columns.
#pragma once

#include "common/chunking.hpp"

#include <Eigen/Core>

#include <cstdint>

namespace posekit::cuda {

/// The smallest scratch budget a device may be given (CudaDeviceOptions::max_chunk_bytes).
constexpr std::uint64_t kMinimumChunkBytes = 4096;

/// The budget used when none is given: large enough that a launch runs for milliseconds, small
/// beside any data-centre GPU's memory.
constexpr std::uint64_t kDefaultChunkBytes = std::uint64_t{256} << 20;

/// The most items (points, particles, rows) in one chunk: keeps every index in an int and every
/// column of a chunk below 2 GiB, the largest pitch of a rectangular copy.
constexpr Eigen::Index kMaxChunkItems = Eigen::Index{1} << 27;

/// The most columns of one assembly tile (65,535 blocks of 32 columns in the grid's y).
constexpr Eigen::Index kMaxTileColumns = Eigen::Index{65535} * 32;

/// The limits of one chunk under a scratch budget of `max_chunk_bytes`.
inline backends::ChunkLimits chunk_limits(std::uint64_t max_chunk_bytes) {
  return {max_chunk_bytes, kMaxChunkItems, kMaxTileColumns};
}

using backends::assembly_tiles;
using backends::items_per_chunk;
using backends::TileShape;

}  // namespace posekit::cuda
